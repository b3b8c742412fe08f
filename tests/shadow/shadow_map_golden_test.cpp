// Golden images of the shadow maps (golden/README.md): per case the
// frame at 200 x 160 (R, G, B, A within 1/255, Z exact) in golden/sm-<case>.exr and the light's
// depth map(s) in golden/sm-<case>-map.exr (exact): channel Z is the first map, every further one
// is Z.<name> as --dump shadowmap names them (cube faces L0.face1 … L0.face5, TSM's unwarped view
// with the trapezoid L0.plain). Maps are 128² to keep the files small.
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

struct MapGolden {
  std::string name;   // golden/sm-<name>.exr and golden/sm-<name>-map.exr
  std::string scene;  // scenes/<scene>.yaml
  std::string_view method;
  std::vector<std::string> overrides;
  size_t maps;        // how many maps the first frame keeps
};

std::vector<MapGolden> mapGoldens() {
  return {
      {"standard", "directional", "shadowmap", {}, 1},  // orthographic ([Hempe 2004, §5.1.2])
      {"tsm", "outdoor", "tsm", {}, 2},         // [Hempe 2004, §4.1]; + L0.plain
      {"pcf", "spot", "shadowmap", {"shadow.pcf=3"}, 1},  // perspective, 3 x 3 PCF
      // [Hempe 2004, §4.2]: 16 positions on the edge of a square area light, accumulated; map of
      // the first.
      {"soft", "spot", "shadowmap", {"lights.0.soft.shape=area16", "lights.0.soft.spacing=0.6"}, 1},
      {"cube", "room", "shadowmap", {}, 6},  // point light: six cube faces
  };
}

std::string goldenPath(const std::string& file) { return std::string(SHADOWREF_SOURCE_DIR) + "/golden/" + file + ".exr"; }

bool updatingGoldens() {
  const char* flag = std::getenv("SHADOWREF_UPDATE_GOLDENS");
  return flag != nullptr && std::string(flag) == "1";
}

FrameResult renderGolden(const MapGolden& g) {
  LoadOptions load;
  load.overrides = {"image.width=200", "image.height=160", "shadow.map_size=128"};
  load.overrides.insert(load.overrides.end(), g.overrides.begin(), g.overrides.end());
  const Scene scene = loadScene(std::string(SHADOWREF_SOURCE_DIR) + "/scenes/" + g.scene + ".yaml", load);
  FrameOptions options;
  options.method = g.method;
  options.keepShadowMaps = true;
  // Written by the reference pipeline, compared with the fast one's frames.
  options.pipeline = updatingGoldens() ? PipelineKind::Reference : PipelineKind::Fast;
  return renderFrame(scene, options);
}

ExrExtras mapChannels(const FrameResult& frame) {
  ExrExtras extras;
  for (size_t i = 0; i < frame.shadowMaps.size(); ++i)
    extras.channels.push_back(
        NamedChannel::floatChannel(i == 0 ? "Z" : "Z." + frame.shadowMapNames[i], frame.shadowMaps[i].values()));
  return extras;
}

// Writes or compares one file; false when it fails.
// On failure the message names a report with the golden, this frame and their difference.
bool checkGolden(const Framebuffer& fb, const ExrExtras& extras, const std::string& path, bool update) {
  if (update) {
    std::filesystem::create_directories(std::filesystem::path(path).parent_path());
    writeExr(fb, path, extras);
    return true;
  }
  const testing::GoldenOutcome outcome =
      testing::checkGoldenExr(std::filesystem::path(path).stem().string(), fb, extras, path);
  INFO(outcome.message);
  CHECK(outcome.passed);
  return outcome.passed;
}

}  // namespace

TEST_CASE("golden: standard, TSM, PCF, soft (16-light accumulation) and cube shadow maps match their EXRs, frame "
          "and map (Z exact, colour within 1/255)", "[golden-sm]") {
  const bool update = updatingGoldens();
  for (const MapGolden& g : mapGoldens()) {
    INFO("golden sm-" << g.name);
    const FrameResult frame = renderGolden(g);
    REQUIRE(frame.framebuffer.hasColor());
    REQUIRE(frame.framebuffer.hasDepth());
    REQUIRE(frame.shadowMaps.size() == g.maps);
    checkGolden(frame.framebuffer, {}, goldenPath("sm-" + g.name), update);
    const Framebuffer holder(frame.shadowMaps[0].width, frame.shadowMaps[0].height);  // no buffers: the maps only
    checkGolden(holder, mapChannels(frame), goldenPath("sm-" + g.name + "-map"), update);
  }
  if (update) WARN("goldens written to golden/ (SHADOWREF_UPDATE_GOLDENS=1): review them with git diff --stat");
}

TEST_CASE("golden: the shadow-map goldens show shadows (some pixels darker than without them)", "[golden-sm]") {
  for (const MapGolden& g : mapGoldens()) {
    INFO("golden sm-" << g.name);
    const FrameResult shadowed = renderGolden(g);
    MapGolden unshadowed = g;
    unshadowed.overrides.push_back("shadow.compare_fail=1");
    const FrameResult lit = renderGolden(unshadowed);
    size_t darker = 0;
    for (size_t i = 0; i < shadowed.framebuffer.color().size(); ++i)
      darker += shadowed.framebuffer.color()[i].g < lit.framebuffer.color()[i].g;
    // 85 for sm-standard: its map fitted to the casters has no acne on the tilted block, which the
    // map over the scene box had and counted.
    CHECK(darker > 50);
  }
}
