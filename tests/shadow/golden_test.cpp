// Golden images of the stencil shadow volumes (golden/README.md).
//
// Each case renders a document scene at 200 x 160 with one method and compares with
// golden/<case>.exr what writeExr would write: colour (R, G, B, A) within 1/255, depth (Z) and
// stencil exactly. `stencil` is the framebuffer's stencil after the frame (the last light's
// counts); with several lights every light's counts after its volume pass are extra channels
// stencil.L0, stencil.L1, ... as `shadowref render --dump stencil` writes them.
//
// SHADOWREF_UPDATE_GOLDENS=1 writes the goldens instead of comparing: scripts/update-goldens.sh.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "image/image_compare.h"
#include "image/image_writer.h"
#include "scene/scene_loader.h"
#include "shadow/frame_renderer.h"
#include "support/golden_report.h"

using namespace shadowref;

namespace {

struct GoldenCase {
  std::string name;   // golden/<name>.exr
  std::string scene;  // scenes/<scene>.yaml
  std::string_view method;
  std::vector<std::string> overrides;
};

std::vector<GoldenCase> goldenCases() {
  std::vector<GoldenCase> cases;
  for (const char* scene : {"room", "pumpkins", "city16", "minimal"})
    for (const char* method : {"zpass", "zfail", "auto"})
      cases.push_back({std::string(scene) + "-" + method, scene, method, {}});
  // Soft shadows ([Kuhn 2016, §3.6]): the ceiling light plus 8 on a square in the Y plane, 9
  // stencils.
  cases.push_back({"room-soft-square_y", "room", "zfail",
                   {"lights.0.soft.shape=square_y", "lights.0.soft.spacing=0.3"}});
  return cases;
}

std::string goldenPath(const std::string& name) { return std::string(SHADOWREF_SOURCE_DIR) + "/golden/" + name + ".exr"; }

bool updatingGoldens() {
  const char* flag = std::getenv("SHADOWREF_UPDATE_GOLDENS");
  return flag != nullptr && std::string(flag) == "1";
}

FrameResult renderCase(const GoldenCase& c) {
  LoadOptions load;
  load.overrides = {"image.width=200", "image.height=160"};
  load.overrides.insert(load.overrides.end(), c.overrides.begin(), c.overrides.end());
  const Scene scene = loadScene(std::string(SHADOWREF_SOURCE_DIR) + "/scenes/" + c.scene + ".yaml", load);
  FrameOptions options;
  options.method = c.method;
  options.keepStencil = true;
  // Goldens are written by the reference pipeline, which defines every byte; the fast one is
  // compared with them.
  options.pipeline = updatingGoldens() ? PipelineKind::Reference : PipelineKind::Fast;
  return renderFrame(scene, options);
}

}  // namespace

TEST_CASE("golden: every shadow-volume method on room, pumpkins, city16, minimal and a soft light matches its EXR "
          "(stencil and Z exact, colour within 1/255)", "[golden]") {
  const bool update = updatingGoldens();
  for (const GoldenCase& c : goldenCases()) {
    const FrameResult frame = renderCase(c);
    const ExrExtras extras = perLightStencilChannels(frame.stencilPerLight, frame.stencilLightNames);
    const std::string path = goldenPath(c.name);
    INFO("golden " << c.name << " (" << path << ")");
    // Not vacuous: every golden holds colour, depth and the stencil of each light.
    REQUIRE(frame.framebuffer.hasColor());
    REQUIRE(frame.framebuffer.hasDepth());
    REQUIRE(frame.framebuffer.hasStencil());
    REQUIRE_FALSE(frame.stencilPerLight.empty());
    if (update) {
      std::filesystem::create_directories(std::filesystem::path(path).parent_path());
      writeExr(frame.framebuffer, path, extras);
      continue;
    }
    // On failure: a report with the golden, this frame and their difference (the message names it).
    const testing::GoldenOutcome outcome = testing::checkGoldenExr(c.name, frame.framebuffer, extras, path);
    INFO(outcome.message);
    CHECK(outcome.passed);
  }
  if (update) WARN("goldens written to golden/ (SHADOWREF_UPDATE_GOLDENS=1): review them with git diff --stat");
}

TEST_CASE("golden: the soft-light golden holds one stencil channel per light, and the lights' shadows differ",
          "[golden]") {
  const FrameResult frame = renderCase(goldenCases().back());
  REQUIRE(frame.stencilPerLight.size() == 9);  // the light plus 8 on a square ([Kuhn 2016, §3.6])
  const ExrExtras extras = perLightStencilChannels(frame.stencilPerLight, frame.stencilLightNames);
  REQUIRE(extras.channels.size() == 9);
  CHECK(extras.channels[0].name == "stencil.L0");
  CHECK(extras.channels[8].name == "stencil.L8");
  // Moved lights throw the shadows elsewhere: the penumbra the soft light is made for.
  CHECK(frame.stencilPerLight[1] != frame.stencilPerLight[0]);
  CHECK(frame.stencilPerLight[1] != frame.stencilPerLight[2]);
}
