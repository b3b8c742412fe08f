// Every shadow method of `shadowref render --method`, and the soft (many-sample) variants of a
// volume and a map method, captured from one of the documents' scenes ([Kuhn 2016, Fig. 5.1,
// 5.2]) and replayed on Mesa's llvmpipe and softpipe as a user does it: `render --capture`, then
// `replay --on osmesa:DRIVER`. Each replay runs in a process of its own (Mesa picks its driver once
// per process). Every framebuffer of the trace (the frame and each shadow map) must agree with
// the reference in the fixed-function mode: differing pixels only on triangle edges and fill-rule
// ties, elsewhere within the bounds of docs/conformance.md.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <string>

#include "support/cli_run.h"

namespace shadowref::testing {

namespace {

// Lines of `text` that start with `prefix` and end with `suffix`.
size_t countLines(const std::string& text, const std::string& prefix, const std::string& suffix = "") {
  size_t n = 0;
  for (size_t at = 0; at < text.size();) {
    const size_t end = std::min(text.find('\n', at), text.size());
    const std::string line = text.substr(at, end - at);
    if (line.starts_with(prefix) && line.ends_with(suffix)) ++n;
    at = end + 1;
  }
  return n;
}

}  // namespace

TEST_CASE("replay: every shadow method's capture agrees with llvmpipe and softpipe", "[trace][cli][conformance]") {
  if (!std::filesystem::exists(std::filesystem::path(SHADOWREF_CLI).parent_path() / "shadowref-gl")) {
    WARN("no shadowref-gl in this build");
    return;
  }
  // A soft light: the light plus 14 on a sphere ([Kuhn 2016, §3.6]), 15 passes. For the map a
  // spot light, one map per sample: a point light's six maps per sample, 91 framebuffers, would
  // replay six times the maps on each driver and test nothing more.
  const std::string soft = "-D lights.0.soft.shape=sphere14";
  const std::string spot = " -D lights.0.type=spot -D 'lights.0.direction=[0, -1, 0]' -D lights.0.spot_cutoff=70";
  // scene, method, overrides, framebuffers in the trace (the frame, then one per shadow map).
  const auto [scene, method, extra, framebuffers] = GENERATE_COPY(table<std::string, std::string, std::string, size_t>({
      {"room", "none", "", 1},
      {"room", "zpass", "", 1},
      {"pumpkins", "zfail", "", 1},
      {"pumpkins", "auto", "", 1},
      {"room", "shadowmap", "", 7},  // the point light's six cube faces
      {"pumpkins", "tsm", "", 7},
      {"room", "zfail", soft, 1},
      {"room", "shadowmap", soft + spot, 16},
  }));
  CAPTURE(scene, method, extra);
  const std::filesystem::path dir = freshScratchDir("method_replay");
  const std::string trace = (dir / "frame.srtrace").string();
  const CliRun capture = runShadowref("render scenes/" + scene + ".yaml --method " + method + " " + extra +
                                      " -D image.width=200 -D image.height=160 -D shadow.map_size=256 --quiet -o " +
                                      (dir / "frame.png").string() + " --capture " + trace);
  CAPTURE(capture.err);
  REQUIRE(capture.status == 0);
  for (const char* on : {"osmesa:llvmpipe", "osmesa:softpipe"}) {
    const CliRun r = runShadowref("replay " + trace + " --on " + on);
    CAPTURE(on, r.out, r.err);
    if (r.err.find("no OSMesa") != std::string::npos) {
      WARN("this build has no OSMesa");
      return;
    }
    CHECK(r.status == 0);
    CHECK_THAT(r.out, Catch::Contains(std::string("actual:   ") + on + " (fixed-function mode)"));
    CHECK_THAT(r.out, Catch::Contains("framebuffer 0 (the frame), 200x160: agrees"));
    // Every framebuffer compared, each agreeing; the frame's every buffer at the asked size.
    CHECK(countLines(r.out, "framebuffer ") == framebuffers);
    CHECK(countLines(r.out, "framebuffer ", ": agrees") == framebuffers);
    CHECK_THAT(r.out, Catch::Contains("colour       32000 pixels"));
    CHECK_THAT(r.out, !Catch::Contains("DIFFERS"));
    CHECK_THAT(r.out, Catch::EndsWith("result: agrees\n"));
  }
}

}  // namespace shadowref::testing
