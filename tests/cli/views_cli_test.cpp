// The teaching views as the command line gives them: the overflow scene's stencil legend stays
// small.
#include <catch2/catch.hpp>

#include <cstdint>
#include <filesystem>
#include <string>

#include "support/cli_run.h"

namespace fs = std::filesystem;
using shadowref::testing::CliRun;
using shadowref::testing::runShadowref;
using shadowref::testing::slurp;
using shadowref::testing::testScratch;

namespace {

fs::path freshDir(const std::string& name) {
  const fs::path dir = testScratch() / ("views-" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// The height in a PNG's IHDR chunk (bytes 20..23, big-endian).
uint32_t pngHeight(const fs::path& file) {
  const std::string bytes = slurp(file);
  REQUIRE(bytes.size() > 24);
  uint32_t h = 0;
  for (int i = 20; i < 24; ++i) h = (h << 8) | uint8_t(bytes[size_t(i)]);
  return h;
}

}  // namespace

TEST_CASE("the overflow scene's stencil legend stays small with 255 saturated counts", "[cli][views]") {
  // Saturating ops, two passes: the 400 x 320 picture holds dozens of distinct counts up to 255.
  const fs::path dir = freshDir("overflow");
  const CliRun r = runShadowref("render scenes/overflow.yaml -D shadow.wrap=false -D shadow.two_sided=false -o '" +
                                (dir / "o.png").string() + "' --dump stencil --quiet");
  REQUIRE(r.status == 0);
  // The ramp legend: 36 rows at glyph scale 2 (view.cpp), whatever the counts.
  CHECK(pngHeight(dir / "o.stencil-L0.png") == 320 + 36);
}
