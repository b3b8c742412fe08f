// The teaching views as the command line gives them: options that do not apply to a method are
// errors (exit 2, nothing written), the overflow scene's stencil legend stays small, stencil values
// read the same in --dump-region and --pixel-history, and the pixel history names lights, clears
// and shadow-map lookups.
#include <catch2/catch.hpp>

#include <cstdint>
#include <filesystem>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "support/cli_run.h"

namespace fs = std::filesystem;
using shadowref::testing::CliRun;
using shadowref::testing::runShadowref;
using shadowref::testing::slurp;
using shadowref::testing::testScratch;

namespace {

fs::path freshDir(const std::string& name) { return shadowref::testing::freshScratchDir("views-" + name); }

// The height in a PNG's IHDR chunk (bytes 20..23, big-endian).
uint32_t pngHeight(const fs::path& file) {
  const std::string bytes = slurp(file);
  REQUIRE(bytes.size() > 24);
  uint32_t h = 0;
  for (int i = 20; i < 24; ++i) h = (h << 8) | uint8_t(bytes[size_t(i)]);
  return h;
}

size_t occurrences(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

}  // namespace

TEST_CASE("every render option is checked against every method: what does not apply exits 2", "[cli][views]") {
  const std::vector<std::string> methods = {"none", "zpass", "zfail", "auto", "shadowmap", "tsm"};
  const std::vector<std::string> volumeMethods = {"zpass", "zfail", "auto"};
  const std::vector<std::string> mapMethods = {"shadowmap", "tsm"};
  auto in = [](const std::vector<std::string>& list, const std::string& m) {
    return std::find(list.begin(), list.end(), m) != list.end();
  };
  struct Option {
    std::string flags;
    std::vector<std::string> appliesTo;
    std::string named = "";  // the flag the refusal names; "": the first of `flags`
  };
  const std::vector<std::string> all = methods;
  const std::vector<Option> options = {
      {"--view volumes", volumeMethods},
      {"--view volumes-overlay", volumeMethods},
      {"--dump stencil", volumeMethods},
      {"--dump-region 0,0,2,2", volumeMethods},
      {"--dump shadowmap", mapMethods},
      {"--dump depth", all},
      {"--dump passes", all},
      {"--dump visibility", all},
      {"--pixel-history 3,3", all},
      {"--dump stencil --stencil-view signed", volumeMethods},
      {"--dump-region 0,0,1,1 --stencil-view unsigned", volumeMethods},
      {"--pixel-history 3,3 --stencil-view signed", volumeMethods, "--stencil-view"},
      {"--stencil-view signed", {}},  // nothing shows stencil counts
  };
  for (const std::string& method : methods)
    for (const Option& option : options) {
      INFO(method << " " << option.flags);
      const fs::path dir = freshDir("applies");
      const CliRun r = runShadowref("render scenes/minimal.yaml -D image.width=16 -D image.height=12 --method " + method +
                                    " " + option.flags + " -o '" + (dir / "o.png").string() + "' --quiet");
      if (in(option.appliesTo, method)) {
        CHECK(r.status == 0);
      } else {
        CHECK(r.status == 2);
        CHECK(fs::is_empty(dir));  // refused before anything is rendered
        const std::string flag = option.named.empty() ? option.flags.substr(0, option.flags.find(' ')) : option.named;
        CHECK(r.err.rfind(flag, 0) == 0);  // the message starts with the option it refuses
      }
    }
  const CliRun shadowmap = runShadowref("render scenes/minimal.yaml --method shadowmap --view volumes -o '" +
                                        (freshDir("msg") / "o.png").string() + "'");
  CHECK(shadowmap.err ==
        "--view volumes: the method 'shadowmap' draws no shadow volumes; it applies to zpass, zfail, auto (--method "
        "NAME)\n");
}

TEST_CASE("the overflow scene's stencil legend stays small with 255 saturated counts", "[cli][views]") {
  // Saturating ops, two passes: the 400 x 320 picture holds dozens of distinct counts up to 255.
  const fs::path dir = freshDir("overflow");
  const CliRun r = runShadowref("render scenes/overflow.yaml -D shadow.wrap=false -D shadow.two_sided=false -o '" +
                                (dir / "o.png").string() + "' --dump stencil --quiet");
  REQUIRE(r.status == 0);
  // The ramp legend: 36 rows at glyph scale 2 (view.cpp), whatever the counts.
  CHECK(pngHeight(dir / "o.stencil-L0.png") == 320 + 36);
}

TEST_CASE("the region dump and the pixel history read the stencil alike: 255 unsigned, -1 signed", "[cli][views]") {
  // The overflow scene with saturating ops clamps the shadow's counts at 255; the image centre's
  // column crosses the shadow (docs/teaching.md, section 4).
  const fs::path dir = freshDir("consistent");
  const std::string base = "render scenes/overflow.yaml -D image.width=100 -D image.height=80 -D shadow.wrap=false "
                           "-D shadow.two_sided=false -o '" + (dir / "o.png").string() + "' --quiet ";
  const CliRun grid = runShadowref(base + "--dump-region 50,0,1,80");
  REQUIRE(grid.status == 0);
  // The first row whose count is 255.
  int y = -1;
  std::istringstream lines(grid.out);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream fields(line);
    int row = 0, count = 0;
    if (fields >> row >> count && count == 255) y = row;
  }
  REQUIRE(y >= 0);
  const std::string pixel = "50," + std::to_string(y);
  const CliRun history = runShadowref(base + "--pixel-history " + pixel);
  REQUIRE(history.status == 0);
  CHECK(history.out.find("stencil after the pass: 255 (in shadow)") != std::string::npos);
  CHECK(history.out.find("; stencil unsigned") != std::string::npos);
  const CliRun signedGrid = runShadowref(base + "--dump-region " + pixel + ",1,1 --stencil-view signed");
  CHECK(signedGrid.out.find(std::to_string(y) + " -1\n") != std::string::npos);
  const CliRun signedHistory = runShadowref(base + "--pixel-history " + pixel + " --stencil-view signed");
  CHECK(signedHistory.out.find("stencil after the pass: -1 (in shadow)") != std::string::npos);
}

TEST_CASE("the pixel history names each fragment's light and the stencil clear before each light", "[cli][views]") {
  // Two lights, 'warm' and 'cool': two volume passes, each opened by a stencil clear to 0.
  const CliRun r = runShadowref("render scenes/two_lights.yaml -D image.width=64 -D image.height=48 --method zfail "
                                "--pixel-history 32,20 -o '" + (freshDir("lights") / "o.png").string() + "' --quiet");
  REQUIRE(r.status == 0);
  CHECK(r.out.find("pass 02-stencil-L0 (light L0 'warm')\n  clear  stencil ") != std::string::npos);
  CHECK(r.out.find("pass 03-lit-L0 (light L0 'warm')") != std::string::npos);
  CHECK(r.out.find("pass 04-stencil-L1 (light L1 'cool')\n  clear  stencil ") != std::string::npos);
  CHECK(r.out.find("pass 05-lit-L1 (light L1 'cool')") != std::string::npos);
  CHECK(occurrences(r.out, "  clear  stencil ") == 2);
  CHECK(occurrences(r.out, " -> 0\n") >= 2);  // each clear leaves 0
  // Every fragment of a light's pass is labelled with that light.
  std::istringstream lines(r.out);
  std::string light;
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("pass ", 0) == 0) {
      const size_t at = line.find("(light ");
      light = at == std::string::npos ? "" : line.substr(at + 7, 2);
    } else if (line.rfind("  draw ", 0) == 0 && !light.empty()) {
      CHECK(line.find("  light " + light + "  ") != std::string::npos);
    }
  }
}

TEST_CASE("the pixel history of a shadow map shows each lookup, and its result follows from r and D", "[cli][views]") {
  // Both lights of two_lights.yaml, at pixels across the frame: every lookup line's verdict is the
  // comparison it prints (r <= D lit, result 1; r > D shadowed, result the compare-fail value 0.4).
  const std::regex lookup(R"(lookup light (L\d) '(\w+)'.* stored D ([0-9.e-]+)  compared r ([0-9.e-]+) (<=|>) D: (lit|shadowed)  result ([0-9.]+))");
  std::map<std::string, int> verdicts;
  for (const char* pixel : {"20,10", "32,20", "40,12", "50,30", "10,5", "30,8"}) {
    INFO(pixel);
    const CliRun r = runShadowref(std::string("render scenes/two_lights.yaml -D image.width=64 -D image.height=48 "
                                              "--method shadowmap --pixel-history ") + pixel + " -o '" +
                                  (freshDir("lookup") / "o.png").string() + "' --quiet");
    REQUIRE(r.status == 0);
    std::istringstream lines(r.out);
    int lookups = 0;
    for (std::string line; std::getline(lines, line);) {
      std::smatch m;
      if (!std::regex_search(line, m, lookup)) continue;
      ++lookups;
      const double d = std::stod(m[3]), rq = std::stod(m[4]);
      const bool lit = m[6] == "lit";
      CHECK((m[5] == "<=") == lit);
      CHECK((rq <= d) == lit);
      CHECK(std::stod(m[7]) == (lit ? 1.0 : 0.4));
      ++verdicts[m[6]];
      CHECK((m[1] == "L0" ? m[2] == "warm" : m[2] == "cool"));
    }
    // Each shaded camera-pass fragment looks up both lights.
    CHECK(lookups % 2 == 0);
    CHECK(lookups >= 2);
  }
  CHECK(verdicts["lit"] > 0);
}
