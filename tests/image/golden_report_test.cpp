// The golden failure report: a deliberately broken golden, fed through the same path the golden
// tests take (testing::checkGoldenExr), produces the case page with the reference, result and
// difference pictures and the index that links it; a matching golden produces nothing.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "image/channel_image.h"
#include "image/difference_image.h"
#include "image/temp_dir.h"
#include "scene/scene_loader.h"
#include "shadow/frame_renderer.h"
#include "support/golden_report.h"

using namespace shadowref;
using shadowref::test::TempDir;

namespace {

namespace fs = std::filesystem;

FrameResult renderMinimal() {
  LoadOptions load;
  load.overrides = {"image.width=40", "image.height=30"};
  const Scene scene = loadScene(std::string(SHADOWREF_SOURCE_DIR) + "/scenes/minimal.yaml", load);
  FrameOptions options;
  options.method = "zfail";
  options.pipeline = PipelineKind::Reference;
  return renderFrame(scene, options);
}

std::string fileText(const fs::path& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("a broken golden produces an HTML report with the reference, result and difference pictures",
          "[image][golden-report]") {
  TempDir dir("golden-report");
  const std::string folder = dir.file("report");
  const FrameResult frame = renderMinimal();
  REQUIRE(frame.framebuffer.hasStencil());

  // The broken golden: the frame with one stencil count raised by one at framebuffer pixel (7, 3).
  Framebuffer broken = frame.framebuffer;
  broken.stencil()[broken.index(7, 3)] = uint8_t(broken.stencil()[broken.index(7, 3)] + 1);
  const std::string golden = dir.file("minimal-broken.exr");
  writeExr(broken, golden);

  const testing::GoldenOutcome outcome = testing::checkGoldenExr("minimal-broken", frame.framebuffer, {}, golden, folder);
  INFO(outcome.message);
  CHECK_FALSE(outcome.passed);
  const fs::path page = fs::path(folder) / "minimal-broken" / "index.html";
  REQUIRE(outcome.page == page.string());
  CHECK(contains(outcome.message, "report: " + page.string()));  // the test output names the page
  REQUIRE(fs::exists(page));
  const std::string html = fileText(page);
  for (const char* picture : {"reference.png", "result.png", "difference.png"}) {
    INFO(picture);
    CHECK(contains(html, std::string("<img src=\"") + picture + "\""));
    const ChannelImage image = readChannelImage((page.parent_path() / picture).string());
    CHECK(image.width >= 40);
  }
  // Only the stencil differs: its own row of pictures is there, and no colour row.
  CHECK(contains(html, "<h3>channel stencil</h3>"));
  CHECK_FALSE(contains(html, "<h3>channel R</h3>"));
  CHECK(contains(html, "FAILED: 1 of 1200 pixels"));
  CHECK(fs::exists(page.parent_path() / "stencil-difference.png"));
  // The difference picture: the one changed pixel (file row 30 - 1 - 3 = 26) is at the top of the
  // scale (white), an unchanged one black.
  const ChannelImage diff = readChannelImage((page.parent_path() / "difference.png").string());
  const int k = heatPixelScale(40, 30);
  auto red = [&](int x, int y) { return diff.data[0][size_t(y * k) * size_t(diff.width) + size_t(x * k)]; };
  CHECK(red(7, 26) == 1.0);
  CHECK(red(0, 0) == 0.0);
  // The index links the case.
  const std::string index = fileText(fs::path(folder) / "index.html");
  CHECK(contains(index, "href=\"minimal-broken/index.html\""));

  // The unbroken golden passes and adds no case.
  const std::string good = dir.file("minimal-good.exr");
  writeExr(frame.framebuffer, good);
  const testing::GoldenOutcome pass = testing::checkGoldenExr("minimal-good", frame.framebuffer, {}, good, folder);
  CHECK(pass.passed);
  CHECK(pass.page.empty());
  CHECK_FALSE(fs::exists(fs::path(folder) / "minimal-good"));
}

TEST_CASE("a frame hash that no longer matches is reported with the reference pipeline's frame", "[image][golden-report]") {
  TempDir dir("hash-report");
  const FrameResult frame = renderMinimal();
  Framebuffer changed = frame.framebuffer;
  changed.color()[changed.index(0, 0)] = glm::vec4(1.0f, 0.0f, 1.0f, 1.0f);
  const std::string page = testing::reportFrames("minimal-hash", frame.framebuffer, changed, "fast pipeline",
                                                 "a test note", dir.file("report"));
  REQUIRE(fs::exists(page));
  const std::string html = fileText(page);
  CHECK(contains(html, "a test note"));
  CHECK(contains(html, "<h3>channel R</h3>"));
  CHECK(contains(html, "FAILED: 1 of 1200 pixels"));
  for (const char* picture : {"reference.png", "result.png", "difference.png"})
    CHECK(fs::exists(fs::path(page).parent_path() / picture));
}

// scripts/update-goldens.sh's dry run points the golden tests' reports at its folder through
// SHADOWREF_GOLDEN_REPORT_DIR; without it they go under the build tree.
TEST_CASE("the golden tests' report folder: SHADOWREF_GOLDEN_REPORT_DIR, else <build>/golden-report",
          "[image][golden-report]") {
  TempDir dir("report-folder");
  const char* before = std::getenv("SHADOWREF_GOLDEN_REPORT_DIR");
  const std::string saved = before ? before : "";
  ::unsetenv("SHADOWREF_GOLDEN_REPORT_DIR");
  CHECK(testing::goldenReportFolder() == std::string(SHADOWREF_BINARY_DIR) + "/golden-report");
  const std::string folder = dir.file("dry-run");
  ::setenv("SHADOWREF_GOLDEN_REPORT_DIR", folder.c_str(), 1);
  CHECK(testing::goldenReportFolder() == folder);
  // A broken golden checked with the default folder, as the golden tests check theirs, lands there.
  const FrameResult frame = renderMinimal();
  Framebuffer broken = frame.framebuffer;
  broken.stencil()[0] = uint8_t(broken.stencil()[0] + 1);
  const std::string golden = dir.file("minimal-broken.exr");
  writeExr(broken, golden);
  const testing::GoldenOutcome outcome = testing::checkGoldenExr("minimal-broken", frame.framebuffer, {}, golden);
  CHECK(outcome.page == (fs::path(folder) / "minimal-broken" / "index.html").string());
  CHECK(fs::exists(outcome.page));
  if (before)
    ::setenv("SHADOWREF_GOLDEN_REPORT_DIR", saved.c_str(), 1);
  else
    ::unsetenv("SHADOWREF_GOLDEN_REPORT_DIR");
}
