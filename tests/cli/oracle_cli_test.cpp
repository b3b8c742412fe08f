// `shadowref render --oracle`: the ray-cast oracle on the user's scene from the command line. It
// reproduces a row of docs/shadow-maps.md's accuracy table (bench/shadow_map_accuracy's figure),
// its counts agree with its error map, and on a frame without shadows every pixel the oracle sees
// shadowed is counted as a missed shadow — the oracle's own answer, cast here independently.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <filesystem>
#include <regex>
#include <string>

#include "image/channel_image.h"
#include "oracle/oracle.h"
#include "scene/scene_loader.h"
#include "support/cli_run.h"

using namespace shadowref;
using shadowref::testing::CliRun;
using shadowref::testing::runShadowref;
using shadowref::testing::testScratch;

namespace {

namespace fs = std::filesystem;

fs::path freshDir(const std::string& name) { return testing::freshScratchDir("oracle-" + name); }

// The figures of the first "oracle L0" line: compared, differ, near edge, elsewhere, false, missed.
std::array<long, 6> figures(const std::string& out) {
  static const std::regex line(
      R"(oracle L0 '[^']*': (\d+) pixels compared, [0-9.]+ % agree; (\d+) differ: (\d+) near an edge, (\d+) elsewhere )"
      R"(\(false shadow (\d+), missed shadow (\d+)\))");
  std::smatch m;
  REQUIRE(std::regex_search(out, m, line));
  std::array<long, 6> f{};
  for (size_t i = 0; i < 6; ++i) f[i] = std::stol(m[i + 1].str());
  return f;
}

// Pixels of an RGB picture with exactly this 8-bit colour.
long countColour(const ChannelImage& picture, std::array<int, 3> colour) {
  long n = 0;
  for (size_t i = 0; i < picture.data[0].size(); ++i) {
    bool same = true;
    for (size_t k = 0; k < 3; ++k) same = same && std::lround(picture.data[k][i] * 255.0) == colour[k];
    n += same;
  }
  return n;
}

}  // namespace

TEST_CASE("render --oracle reproduces docs/shadow-maps.md's accuracy table: room-spot, standard, offset, 128² is "
          "1.76 % wrong", "[cli][oracle]") {
  const fs::path dir = freshDir("table");
  const std::string out = (dir / "room-spot.png").string();
  // The table's scene: the room's light as a spot straight down, at the scene's own 800 x 640.
  const CliRun r = runShadowref(
      "render scenes/room.yaml --method shadowmap -D shadow.map_size=128 -D lights.0.type=spot "
      "-D 'lights.0.direction=[0, -1, 0]' -D lights.0.spot_cutoff=70 --oracle -o '" + out + "'");
  INFO(r.out << r.err);
  REQUIRE(r.status == 0);
  CHECK(r.out.find(", 1.76 % wrong") != std::string::npos);
  // The error map shows what the line counts: red false shadows, blue missed ones, paler near an
  // edge.
  const std::array<long, 6> f = figures(r.out);
  CHECK(f[1] == f[2] + f[3]);
  CHECK(f[1] == f[4] + f[5]);
  const ChannelImage errors = readChannelImage((dir / "room-spot.oracle-errors-L0.png").string());
  CHECK(countColour(errors, {255, 0, 0}) + countColour(errors, {255, 160, 160}) == f[4]);
  CHECK(countColour(errors, {0, 64, 255}) + countColour(errors, {150, 180, 255}) == f[5]);
  CHECK(countColour(errors, {200, 200, 200}) + countColour(errors, {90, 90, 90}) == f[0] - f[1]);
  CHECK(fs::exists(dir / "room-spot.oracle-L0.png"));
}

TEST_CASE("render --oracle: without shadows every pixel the light does not see is a missed shadow, and z-fail agrees "
          "with the oracle everywhere on the minimal scene", "[cli][oracle]") {
  const fs::path dir = freshDir("minimal");
  const std::string size = "-D image.width=160 -D image.height=120";
  LoadOptions load;
  load.overrides = {"image.width=160", "image.height=120"};
  const Scene scene = loadScene(std::string(SHADOWREF_SOURCE_DIR) + "/scenes/minimal.yaml", load);
  REQUIRE(scene.lights.at(0).type == LightType::Point);  // every hit is compared
  const oracle::OracleImage o = oracle::castOracle(scene, scene.lights.at(0));
  long hits = 0, shadowed = 0;
  for (size_t i = 0; i < o.hitMask.size(); ++i) {
    hits += o.hitMask[i];
    shadowed += o.hitMask[i] && !o.lit[i];
  }
  REQUIRE(shadowed > 50);  // the box's shadow on the ground

  const CliRun none = runShadowref("render scenes/minimal.yaml " + size + " --method none --oracle -o '" +
                                   (dir / "none.png").string() + "'");
  INFO(none.out << none.err);
  REQUIRE(none.status == 0);
  const std::array<long, 6> fn = figures(none.out);
  CHECK(fn[0] == hits);
  CHECK(fn[4] == 0);          // nothing is rendered in shadow
  CHECK(fn[5] == shadowed);   // so every shadowed point is missed
  // The ray-traced visibility picture: black exactly where the light does not see a hit.
  const ChannelImage traced = readChannelImage((dir / "none.oracle-L0.png").string());
  long black = 0;
  for (double v : traced.data[0]) black += v == 0.0;
  CHECK(black == shadowed);

  const CliRun zfail = runShadowref("render scenes/minimal.yaml " + size + " --method zfail --oracle -o '" +
                                    (dir / "zfail.png").string() + "'");
  INFO(zfail.out);
  REQUIRE(zfail.status == 0);
  CHECK(zfail.out.find("100.00 % agree; 0 differ") != std::string::npos);
  CHECK(zfail.out.find("map test") == std::string::npos);  // a volume method has no map
}
