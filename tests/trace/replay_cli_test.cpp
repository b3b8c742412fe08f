// `shadowref render --capture` and `shadowref replay` as a user runs them: a capture replays to
// exit 0 on both pipelines with a report; a truncated or garbled trace exits 2 with
// "file: byte N: ..." and no report; bad usage exits 2.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "support/cli_run.h"

namespace shadowref::testing {

namespace {

std::string captureMinimal(const std::filesystem::path& dir) {
  const std::string trace = (dir / "minimal.srtrace").string();
  const CliRun r = runShadowref("render scenes/minimal.yaml -D image.width=48 -D image.height=32 --quiet -o " +
                                (dir / "minimal.png").string() + " --capture " + trace);
  REQUIRE(r.status == 0);
  return trace;
}

}  // namespace

TEST_CASE("replay: a capture of the minimal scene replays on both pipelines, with a report", "[trace][cli]") {
  const std::filesystem::path dir = testScratch() / "replay_cli";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string trace = captureMinimal(dir);
  for (const char* on : {"reference", "fast"}) {
    const CliRun r = runShadowref(std::string("replay ") + trace + " --on " + on + " --report " + (dir / on).string());
    CAPTURE(on, r.out, r.err);
    CHECK(r.status == 0);
    CHECK_THAT(r.out, Catch::Contains("result: agrees"));
    CHECK_THAT(r.out, Catch::Contains("stencil      1536 pixels"));
    CHECK(std::filesystem::exists(dir / on / "index.html"));
    CHECK(std::filesystem::exists(dir / on / "fb0-stencil-difference.png"));
  }
}

TEST_CASE("replay: a truncated or garbled trace exits 2 with its byte offset", "[trace][cli]") {
  const std::filesystem::path dir = testScratch() / "replay_cli_bad";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string trace = captureMinimal(dir);
  const std::string bytes = slurp(trace);
  const std::string cut = (dir / "cut.srtrace").string();
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, 1000);
  CliRun r = runShadowref("replay " + cut + " --report " + (dir / "report").string());
  CHECK(r.status == 2);
  CHECK_THAT(r.err, Catch::StartsWith(cut + ": byte "));
  CHECK_THAT(r.err, Catch::Contains("truncated"));
  CHECK_FALSE(std::filesystem::exists(dir / "report"));
  const std::string other = (dir / "other.srtrace").string();
  std::ofstream(other, std::ios::binary) << std::string("SRTRACE\0\x07\0\0\0", 12);
  r = runShadowref("replay " + other);
  CHECK(r.status == 2);
  CHECK(r.err == other + ": byte 8: format version 7, this build reads version 1\n");
  r = runShadowref("replay " + trace + " --on vulkan");
  CHECK(r.status == 2);
  r = runShadowref("render scenes/minimal.yaml --capture " + (dir / "x.srtrace").string() + " --pixel-history 1,1");
  CHECK(r.status == 2);
  CHECK_THAT(r.err, Catch::Contains("--capture: cannot be combined with --pixel-history"));
}

}  // namespace shadowref::testing

namespace shadowref::testing {

// `replay --on egl:llvmpipe` as a user types it: shadowref hands it to shadowref-gl, which replays
// through EGL's surfaceless platform and compares with the reference in the fixed-function mode.
TEST_CASE("replay: --on egl:llvmpipe runs through shadowref-gl", "[trace][cli][egl]") {
  if (!std::filesystem::exists(std::filesystem::path(SHADOWREF_CLI).parent_path() / "shadowref-gl")) {
    WARN("no shadowref-gl in this build");
    return;
  }
  const std::filesystem::path dir = testScratch() / "replay_cli_egl";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string trace = captureMinimal(dir);
  CliRun r = runShadowref("replay " + trace + " --on egl:llvmpipe");
  CAPTURE(r.out, r.err);
  if (r.err.find("no EGL") != std::string::npos) {
    WARN("this build has no EGL");
    return;
  }
  CHECK(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains("actual:   egl:llvmpipe (fixed-function mode)"));
  CHECK_THAT(r.out, Catch::Contains("result: agrees"));
}

}  // namespace shadowref::testing
