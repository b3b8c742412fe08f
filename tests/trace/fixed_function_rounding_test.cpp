// The fixed-function replay rounds what GL's float vertex pipeline holds in float: the clip
// coordinates and each vertex colour. The values below are not representable in float, so a
// conversion the compiler turned into a copy (GCC 12.2's vectorizer did, to the clip coordinates)
// leaves them unrounded. The expected floats are written out by hand (binary32 nearest to each).
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "gl/fragment_shader.h"
#include "trace/trace_replay.h"

namespace shadowref::trace {

namespace {

// Round to nearest binary32, by hand: 0.1 = 0x3DCCCCCD, 0.2 = 0x3E4CCCCD, 1/3 = 0x3EAAAAAB,
// 0.7 = 0x3F333333, exactly these decimals.
constexpr double kTenth = 0.100000001490116119384765625;
constexpr double kFifth = 0.20000000298023223876953125;
constexpr double kThird = 0.3333333432674407958984375;
constexpr double kSevenTenths = 0.699999988079071044921875;

}  // namespace

TEST_CASE("fixed-function replay: clip coordinates and vertex colours come out rounded to float", "[trace]") {
  DrawCommand draw;
  ClipVertex v;
  v.position = glm::dvec4(0.1, -0.2, 1.0 / 3.0, 1.0 + 1e-12);
  // Three vertices, each a different permutation, so that every lane of a vector copy is seen.
  draw.vertices = {v, v, v};
  draw.vertices[1].position = glm::dvec4(1.0 / 3.0, 0.1, 0.7, 1.0);
  draw.vertices[2].position = glm::dvec4(-0.7, 1.0 / 3.0, 0.2, 0.1);
  const ConstantColorShader shader(glm::dvec4(0.7, 1.0 / 3.0, 0.1, 0.2));
  const std::vector<ClipVertex> out = fixedFunctionVertices(draw, &shader);
  REQUIRE(out.size() == 3);
  CHECK(out[0].position == glm::dvec4(kTenth, -kFifth, kThird, 1.0));
  CHECK(out[1].position == glm::dvec4(kThird, kTenth, kSevenTenths, 1.0));
  CHECK(out[2].position == glm::dvec4(-kSevenTenths, kThird, kFifth, kTenth));
  for (const ClipVertex& o : out) {
    CHECK(o.varyings[0] == kSevenTenths);
    CHECK(o.varyings[1] == kThird);
    CHECK(o.varyings[2] == kTenth);
    CHECK(o.varyings[3] == kFifth);
  }
  // The hand-written constants are the floats' values, not the doubles they round.
  CHECK(kTenth != 0.1);
  CHECK(double(std::nextafter(float(kTenth), 0.0f)) < 0.1);
  // Without a shader only the positions are converted.
  const std::vector<ClipVertex> plain = fixedFunctionVertices(draw, nullptr);
  CHECK(plain[1].position == out[1].position);
}

// The rounding above is proved for fixedFunctionVertices only: no other hand-written round trip
// (a narrowing to float widened again in the same expression) may be in src/, where the compiler
// could drop it unseen. A float that is stored, compared in float or bit-cast is not a round trip.
TEST_CASE("src/ writes no double -> float -> double round trip in one expression", "[trace][docs]") {
  namespace fs = std::filesystem;
  const std::regex roundTrip(
      R"((double|dvec[234])\s*\(\s*(float\s*\(|static_cast<float>|glm::vec[234]\s*\(|vec[234]\s*\())"
      R"(|static_cast<(double|glm::dvec[234])>\s*\(\s*(float\s*\(|static_cast<float>|glm::vec[234]\s*\())");
  int files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(fs::path(SHADOWREF_SOURCE_DIR) / "src")) {
    const std::string ext = entry.path().extension().string();
    if (ext != ".cpp" && ext != ".h") continue;
    ++files;
    std::ifstream in(entry.path());
    std::string line;
    for (int n = 1; std::getline(in, line); ++n) {
      const std::string code = line.substr(0, line.find("//"));  // comments may name the forms
      if (std::regex_search(code, roundTrip)) FAIL_CHECK(entry.path().string() << ":" << n << ": " << line);
    }
  }
  CHECK(files > 100);
  // The pattern finds the forms it is for.
  for (const char* bad : {"x = double(float(y));", "p = glm::dvec4(glm::vec4(q));", "d = static_cast<double>(static_cast<float>(e));",
                          "v = dvec2(vec2(w));"}) {
    INFO(bad);
    CHECK(std::regex_search(std::string(bad), roundTrip));
  }
}

}  // namespace shadowref::trace
