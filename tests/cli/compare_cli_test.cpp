// `shadowref compare` against hand-made images: every option, the metrics against values worked
// out by hand, idiff's thresholds and exit codes (0 PASS, 1 WARNING, 2 FAILURE, 3 sizes or
// channels differ, 4 bad input), the difference heat map and the JSON report; and the stencil
// change that idiff (run too where installed) passes.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "image/channel_image.h"
#include "image/difference_image.h"
#include "image/image_writer.h"
#include "support/cli_run.h"

using namespace shadowref;
using shadowref::testing::CliRun;
using shadowref::testing::runShadowref;
using shadowref::testing::testScratch;

namespace {

namespace fs = std::filesystem;

fs::path freshDir(const std::string& name) { return testing::freshScratchDir("compare-" + name); }

// A 10x10 RGB PNG, every pixel (100, 100, 100), except that the first `changed` pixels of the
// top row have R = 100 + delta.
std::string greyPng(const fs::path& dir, const std::string& name, int changed, int delta, int width = 10) {
  Image8 image;
  image.width = width;
  image.height = 10;
  image.channels = 3;
  image.pixels.assign(size_t(width) * 10 * 3, 100);
  for (int x = 0; x < changed; ++x) image.pixels[size_t(x) * 3] = uint8_t(100 + delta);
  const std::string path = (dir / name).string();
  writePng8(image, path);
  return path;
}

// An EXR with one 32-bit integer channel "count" (4x1), values as given (file order = framebuffer
// order for a single row).
std::string countExr(const fs::path& dir, const std::string& name, std::vector<uint32_t> counts) {
  Framebuffer fb(int(counts.size()), 1);
  ExrExtras extras;
  extras.channels.push_back(NamedChannel::uintChannel("count", std::move(counts)));
  const std::string path = (dir / name).string();
  writeExr(fb, path, extras);
  return path;
}

// A framebuffer's stencil as EXR (R, G, B, A, Z and the stencil as UINT32), one pixel's count set.
std::string stencilExr(const fs::path& dir, const std::string& name, uint8_t count) {
  Framebuffer fb(4, 4);
  fb.ensureColor();
  fb.ensureDepth();
  fb.ensureStencil();
  fb.stencil()[fb.index(2, 1)] = count;
  const std::string path = (dir / name).string();
  writeExr(fb, path);
  return path;
}

std::string q(const std::string& path) { return "'" + path + "'"; }

}  // namespace

TEST_CASE("compare: a stencil count 1 -> 2 FAILS at idiff's default threshold, and PASSES when equal",
          "[cli][compare]") {
  // idiff reads the UINT32 stencil normalised to [0, 1]: 1 and 2 become 2.3e-10 and 4.7e-10, a
  // difference far below its default -fail 1e-6, and it reports PASS. Here the counts are integers.
  const fs::path dir = freshDir("stencil");
  const std::string one = stencilExr(dir, "one.exr", 1), two = stencilExr(dir, "two.exr", 2);
  const CliRun r = runShadowref("compare " + q(one) + " " + q(two) + " --fail 1e-6");
  INFO(r.out << r.err);
  CHECK(r.status == 2);
  CHECK(r.out.find("FAILED: 1 of 16 pixels") != std::string::npos);
  const CliRun json = runShadowref("compare " + q(one) + " " + q(two) + " --fail 1e-6 --json");
  const nlohmann::json j = nlohmann::json::parse(json.out);
  CHECK(j["verdict"] == "FAILURE");
  bool sawStencil = false;
  for (const auto& c : j["channels"]) {
    if (c["name"] != "stencil") continue;
    sawStencil = true;
    CHECK(c["integer"] == true);
    CHECK(c["max_abs"] == 1.0);
    CHECK(c["max_at"] == nlohmann::json::array({2, 2}));  // framebuffer row 1 of 4 is file row 2
  }
  CHECK(sawStencil);
  CHECK(runShadowref("compare " + q(one) + " " + q(stencilExr(dir, "one-again.exr", 1))).status == 0);
  // idiff itself (OpenImageIO's, where installed) passes the same pair: the miss compare exists for.
  if (testing::runShell("command -v idiff").status != 0) {
    WARN("no idiff on this machine: its PASS on the stencil change is not checked");
    return;
  }
  const CliRun idiff = testing::runShell("idiff " + q(one) + " " + q(two));
  INFO(idiff.out << idiff.err);
  CHECK(idiff.status == 0);
  CHECK(idiff.out.find("PASS") != std::string::npos);
}

TEST_CASE("compare --modulo 256 compares integer channels as an 8-bit stencil holds them", "[cli][compare]") {
  const fs::path dir = freshDir("modulo");
  const std::string a = countExr(dir, "a.exr", {1, 0, 5, 7});
  const std::string b = countExr(dir, "b.exr", {257, 256, 5, 8});
  const CliRun exact = runShadowref("compare " + q(a) + " " + q(b) + " --json");
  const nlohmann::json je = nlohmann::json::parse(exact.out);
  CHECK(exact.status == 2);
  CHECK(je["failed_pixels"] == 3);
  CHECK(je["channels"][0]["max_abs"] == 256.0);
  const CliRun wrapped = runShadowref("compare " + q(a) + " " + q(b) + " --modulo 256 --json");
  const nlohmann::json jw = nlohmann::json::parse(wrapped.out);
  CHECK(wrapped.status == 2);           // 7 against 8 still differs
  CHECK(jw["failed_pixels"] == 1);
  CHECK(jw["channels"][0]["max_abs"] == 1.0);
  // Integer PSNR uses the 8-bit peak 255: rmse = sqrt(1/4) = 0.5, 20 log10(255 / 0.5).
  CHECK(jw["channels"][0]["psnr"].get<double>() == Approx(20.0 * std::log10(510.0)));
  CHECK(runShadowref("compare " + q(a) + " " + q(countExr(dir, "c.exr", {257, 256, 261, 263})) + " --modulo 256")
            .status == 0);
  CHECK(runShadowref("compare " + q(a) + " " + q(b) + " --modulo 0").status == 4);
}

TEST_CASE("compare: metrics per channel match hand-computed values", "[cli][compare]") {
  const fs::path dir = freshDir("metrics");
  const std::string a = greyPng(dir, "a.png", 0, 0), b = greyPng(dir, "b.png", 3, 10);
  const CliRun r = runShadowref("compare " + q(a) + " " + q(b) + " --json");
  INFO(r.out << r.err);
  REQUIRE(r.status == 2);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  CHECK(j["verdict"] == "FAILURE");
  CHECK(j["width"] == 10);
  CHECK(j["failed_pixels"] == 3);
  CHECK(j["failed_percent"].get<double>() == Approx(3.0));
  const auto& red = j["channels"][0];
  REQUIRE(red["name"] == "R");
  const double d = 10.0 / 255.0;
  CHECK(red["integer"] == false);
  CHECK(red["max_abs"].get<double>() == Approx(d));
  CHECK(red["max_at"] == nlohmann::json::array({0, 0}));
  CHECK(red["mean_abs"].get<double>() == Approx(3.0 * d / 100.0));
  const double rmse = std::sqrt(3.0 * d * d / 100.0);
  CHECK(red["rmse"].get<double>() == Approx(rmse));
  CHECK(red["psnr"].get<double>() == Approx(20.0 * std::log10(1.0 / rmse)));
  CHECK(red["over_tolerance"] == 3);
  CHECK(red["over_tolerance_percent"].get<double>() == Approx(3.0));
  CHECK(j["channels"][1]["max_abs"] == 0.0);
  CHECK(j["channels"][1]["psnr"] == "inf");
  // The text report says the same.
  const CliRun text = runShadowref("compare " + q(a) + " " + q(b));
  CHECK(text.out.find("FAILED: 3 of 100 pixels (3.000%)") != std::string::npos);
  CHECK(text.out.find("RMSE") != std::string::npos);
  CHECK(text.out.find("PSNR") != std::string::npos);
}

TEST_CASE("compare: idiff's thresholds decide PASS, WARNING and FAILURE", "[cli][compare]") {
  const fs::path dir = freshDir("thresholds");
  // 3 of 100 pixels differ in R by 10/255 = 0.0392.
  const std::string a = greyPng(dir, "a.png", 0, 0), b = greyPng(dir, "b.png", 3, 10);
  const std::string ab = q(a) + " " + q(b) + " ";
  auto status = [&](const std::string& options) {
    const CliRun r = runShadowref("compare " + ab + options);
    INFO(options << "\n" << r.out << r.err);
    return r.status;
  };
  CHECK(status("") == 2);                                        // exact: 3 pixels fail
  CHECK(status("--fail 0.05") == 0);                             // within the tolerance
  CHECK(status("--tolerance 0.039") == 2);                       // the old name, just below
  CHECK(status("--channel-tolerance R=0.04") == 0);              // per channel
  CHECK(status("--fail-percent 5") == 1);                        // 3 % allowed, but over the warning level
  CHECK(status("--fail-percent 2") == 2);                        // 3 % > 2 %
  CHECK(status("--fail-percent 5 --warn-percent 5") == 0);       // both shares allow 3 %
  CHECK(status("--fail-percent 5 --hard-fail 0.02") == 2);       // 0.039 > the hard limit
  CHECK(status("--allow-failures 3") == 1);                      // 3 allowed: a warning
  CHECK(status("--allow-failures 2") == 2);
  CHECK(status("--fail 0.05 --warn 0.01") == 1);                 // over the warning level only
  CHECK(status("--fail 0.05 --warn 0.01 --warn-percent 3") == 0);  // 3 % is not more than 3 %
  CHECK(status("--fail 0.05 --hard-warn 0.03") == 1);            // no pixel over a level, but 0.039 > 0.03
  const CliRun warn = runShadowref("compare " + ab + "--fail-percent 5");
  CHECK(warn.out.find("WARNING: 3 of 100 pixels") != std::string::npos);
}

TEST_CASE("compare: sizes or channel sets that differ exit 3, bad input exits 4", "[cli][compare]") {
  const fs::path dir = freshDir("mismatch");
  const std::string a = greyPng(dir, "a.png", 0, 0), wide = greyPng(dir, "wide.png", 0, 0, 12);
  const CliRun sizes = runShadowref("compare " + q(a) + " " + q(wide));
  CHECK(sizes.status == 3);
  CHECK(sizes.out.find("sizes differ: 10x10 vs 12x10") != std::string::npos);
  const std::string counts = countExr(dir, "counts.exr", {1, 2, 3, 4});
  const std::string four = greyPng(dir, "four.png", 0, 0, 4);
  CHECK(runShadowref("compare " + q(counts) + " " + q(four)).status == 3);  // 4x1 against 4x10
  CHECK(runShadowref("compare " + q(a) + " " + q((dir / "missing.png").string())).status == 4);
  CHECK(runShadowref("compare " + q(a) + " " + q(a) + " --channel-tolerance R").status == 4);
  CHECK(runShadowref("compare " + q(a) + " " + q(a) + " --channels R,stencil").status == 4);
  CHECK(runShadowref("compare " + q(a) + " " + q(a) + " --diff-channel Z --diff " + q((dir / "d.png").string()))
            .status == 4);
  CHECK(runShadowref("compare " + q(a) + " " + q(a) + " --fail-percent 101").status == 4);
  CHECK(runShadowref("compare " + q(a) + " " + q(a) + " --no-such-option").status == 4);
  CHECK_FALSE(fs::exists(dir / "d.png"));
}

TEST_CASE("compare --channels compares only the named channels", "[cli][compare]") {
  const fs::path dir = freshDir("channels");
  const std::string a = greyPng(dir, "a.png", 0, 0), b = greyPng(dir, "b.png", 3, 10);  // only R differs
  CHECK(runShadowref("compare " + q(a) + " " + q(b) + " --channels G,B").status == 0);
  const CliRun r = runShadowref("compare " + q(a) + " " + q(b) + " --channels R --json");
  CHECK(r.status == 2);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  REQUIRE(j["channels"].size() == 1);
  CHECK(j["channels"][0]["name"] == "R");
}

TEST_CASE("compare --diff writes a heat map with a colour scale: black where equal, white at the top",
          "[cli][compare]") {
  const fs::path dir = freshDir("diff");
  const std::string a = greyPng(dir, "a.png", 0, 0), b = greyPng(dir, "b.png", 3, 10);
  const std::string diff = (dir / "sub" / "diff.png").string();
  const CliRun r = runShadowref("compare " + q(a) + " " + q(b) + " --diff " + q(diff));
  INFO(r.out << r.err);
  CHECK(r.status == 2);
  CHECK(r.out.find("difference picture: " + diff) != std::string::npos);
  const ChannelImage picture = readChannelImage(diff);
  const int k = heatPixelScale(10, 10);  // 8 (at most): 10 pixels drawn 80 across
  REQUIRE(k == 8);
  CHECK(picture.width == 104);  // widened to the scale's minimum bar of 96 and its margins
  CHECK(picture.height > 80);   // the scale strip below
  auto rgb = [&](int x, int y) {
    const size_t i = size_t(y) * size_t(picture.width) + size_t(x);
    return std::array<int, 3>{int(std::lround(picture.data[0][i] * 255)), int(std::lround(picture.data[1][i] * 255)),
                              int(std::lround(picture.data[2][i] * 255))};
  };
  // Pixel (1, 0) differs by the largest difference, the top of the scale: white. (5, 5): equal.
  CHECK(rgb(1 * k + 3, 0 * k + 3) == std::array<int, 3>{255, 255, 255});
  CHECK(rgb(5 * k + 3, 5 * k + 3) == std::array<int, 3>{0, 0, 0});
  // With the scale's top at twice the difference the pixel is drawn at t = 0.5: heatColour's red.
  const std::string half = (dir / "half.png").string();
  runShadowref("compare " + q(a) + " " + q(b) + " --diff " + q(half) + " --diff-scale " + std::to_string(20.0 / 255.0));
  const ChannelImage halfPicture = readChannelImage(half);
  const auto red = heatColour(0.5);
  CHECK(std::lround(halfPicture.data[0][size_t(3) * size_t(halfPicture.width) + 3] * 255) == red[0]);
  CHECK(red == std::array<uint8_t, 3>{230, 30, 40});
  // One channel's difference: G is equal everywhere, so the map is black.
  const std::string green = (dir / "green.png").string();
  runShadowref("compare " + q(a) + " " + q(b) + " --diff " + q(green) + " --diff-channel G");
  const ChannelImage greenPicture = readChannelImage(green);
  for (int y = 0; y < 80; ++y)
    for (int x = 0; x < 80; ++x) REQUIRE(greenPicture.data[0][size_t(y) * 104 + size_t(x)] == 0.0);
  // --diff-only-if-different writes nothing for equal images.
  const std::string none = (dir / "none.png").string();
  CHECK(runShadowref("compare " + q(a) + " " + q(a) + " --diff " + q(none) + " --diff-only-if-different").status == 0);
  CHECK_FALSE(fs::exists(none));
}
