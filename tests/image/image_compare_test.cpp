#include <cmath>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include <catch2/catch.hpp>
#include <OpenImageIO/imageio.h>

#include "image/image_compare.h"
#include "image/image_writer.h"
#include "image/temp_dir.h"

using namespace shadowref;
using shadowref::test::TempDir;

namespace {

// A 4x3 framebuffer with colour, depth and stencil, every pixel different.
Framebuffer makeFramebuffer() {
  Framebuffer fb(4, 3);
  fb.ensureColor();
  fb.ensureDepth();
  fb.ensureStencil();
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x) {
      fb.color()[fb.index(x, y)] = glm::vec4(float(x) / 8.0f, float(y) / 4.0f, 0.5f, 1.0f);
      fb.depthCodes()[fb.index(x, y)] = fb.depthCodec().encode(double(x + 4 * y) / 16.0);
      fb.stencil()[fb.index(x, y)] = uint8_t(x + y);
    }
  return fb;
}

ChannelImage oneChannel(const std::string& name, std::vector<double> values, int w, int h) {
  ChannelImage image;
  image.width = w;
  image.height = h;
  image.names = {name};
  image.data = {std::move(values)};
  return image;
}

bool containsText(const std::string& haystack, const std::string& needle) {
  return haystack.find(needle) != std::string::npos;
}

}  // namespace

TEST_CASE("identical EXR files compare equal with zero differences", "[image]") {
  TempDir dir("compare-same");
  writeExr(makeFramebuffer(), dir.file("a.exr"));
  writeExr(makeFramebuffer(), dir.file("b.exr"));
  CompareResult r = compareImages(dir.file("a.exr"), dir.file("b.exr"), Tolerances{});
  CHECK(r.passed);
  CHECK(r.structuralError.empty());
  REQUIRE(r.channels.size() == 6);
  for (const ChannelStats& s : r.channels) {
    CHECK(s.maxAbsDiff == 0.0);
    CHECK(s.failCount == 0);
  }
  CHECK(containsText(formatReport(r), "PASSED"));
}

TEST_CASE("compare finds a single changed stencil pixel and reports both row conventions", "[image]") {
  TempDir dir("compare-one-pixel");
  Framebuffer a = makeFramebuffer();
  Framebuffer b = makeFramebuffer();
  b.stencil()[b.index(2, 0)] = 7;  // was 2: framebuffer row 0 is the file's last row, y = 2
  writeExr(a, dir.file("a.exr"));
  writeExr(b, dir.file("b.exr"));
  CompareResult r = compareImages(dir.file("a.exr"), dir.file("b.exr"), Tolerances{});
  CHECK_FALSE(r.passed);
  CHECK(r.failedPixels == 1);
  REQUIRE(r.firstFailures.size() == 1);
  const PixelFailure& f = r.firstFailures[0];
  CHECK(f.x == 2);
  CHECK(f.y == 2);
  CHECK(f.glY == 0);
  CHECK(f.failingChannels == std::vector<std::string>{"stencil"});
  for (const ChannelStats& s : r.channels) {
    if (s.name == "stencil") {
      CHECK(s.maxAbsDiff == 5.0);
      CHECK(s.meanAbsDiff == 5.0 / 12.0);
      CHECK(s.failCount == 1);
      CHECK(s.maxX == 2);
      CHECK(s.maxY == 2);
    } else {
      CHECK(s.failCount == 0);
    }
  }
  const std::string report = formatReport(r);
  CHECK(containsText(report, "FAILED: 1 of 12 pixels"));
  CHECK(containsText(report, "(2, 2) fb row 0: stencil A=2 B=7"));
}

TEST_CASE("compare respects each channel's absolute tolerance", "[image]") {
  ChannelImage a = oneChannel("R", {0.5, 0.5}, 2, 1);
  ChannelImage b = oneChannel("R", {0.5 + 1.0 / 512, 0.5 - 1.0 / 64}, 2, 1);  // exact differences
  Tolerances loose;
  loose.perChannel["R"] = 1.0 / 64;  // a difference equal to the tolerance passes
  CHECK(compareChannelImages(a, b, loose).passed);
  Tolerances golden = Tolerances::golden();  // R within 1/255 = 0.0039
  CompareResult r = compareChannelImages(a, b, golden);
  CHECK_FALSE(r.passed);
  REQUIRE(r.firstFailures.size() == 1);
  CHECK(r.firstFailures[0].x == 1);
  Tolerances exact;
  CHECK(compareChannelImages(a, b, exact).failedPixels == 2);
  Tolerances fallback;
  fallback.fallback = 0.02;
  CHECK(compareChannelImages(a, b, fallback).passed);
}

TEST_CASE("compare treats NaN against a number as a failure and NaN against NaN as equal", "[image]") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  ChannelImage a = oneChannel("Z", {nan, nan, inf}, 3, 1);
  ChannelImage b = oneChannel("Z", {nan, 0.5, inf}, 3, 1);
  Tolerances huge;
  huge.fallback = 1e30;
  CompareResult r = compareChannelImages(a, b, huge);
  CHECK(r.failedPixels == 1);
  REQUIRE(r.firstFailures.size() == 1);
  CHECK(r.firstFailures[0].x == 1);
}

TEST_CASE("compare reports at most maxReported pixels but counts them all", "[image]") {
  ChannelImage a = oneChannel("G", std::vector<double>(20, 0.0), 5, 4);
  ChannelImage b = oneChannel("G", std::vector<double>(20, 1.0), 5, 4);
  CompareResult r = compareChannelImages(a, b, Tolerances{}, 3);
  CHECK(r.failedPixels == 20);
  REQUIRE(r.firstFailures.size() == 3);
  CHECK(r.firstFailures[2].x == 2);
  CHECK(r.firstFailures[2].y == 0);
  CHECK(r.firstFailures[2].glY == 3);
  CHECK(containsText(formatReport(r), "... and 17 more"));
}

TEST_CASE("compare matches channels by name, not by position", "[image]") {
  ChannelImage a;
  a.width = 1;
  a.height = 1;
  a.names = {"R", "stencil"};
  a.data = {{0.25}, {3.0}};
  ChannelImage b = a;
  b.names = {"stencil", "R"};
  b.data = {{3.0}, {0.25}};
  CHECK(compareChannelImages(a, b, Tolerances{}).passed);
}

TEST_CASE("different sizes or channel sets fail with a message saying what differs", "[image]") {
  ChannelImage a = oneChannel("R", {0, 0}, 2, 1);
  CompareResult sizes = compareChannelImages(a, oneChannel("R", {0, 0}, 1, 2), Tolerances{});
  CHECK_FALSE(sizes.passed);
  CHECK(sizes.structuralError == "sizes differ: 2x1 vs 1x2");
  CompareResult names = compareChannelImages(a, oneChannel("Z", {0, 0}, 2, 1), Tolerances{});
  CHECK_FALSE(names.passed);
  CHECK(names.structuralError == "channel sets differ: only in A: R; only in B: Z");
  CHECK(containsText(formatReport(names), "FAILED: channel sets differ"));
}

TEST_CASE("PNG channels compare as colour normalised to [0, 1]", "[image]") {
  TempDir dir("compare-png");
  Framebuffer a(2, 1), b(2, 1);
  a.ensureColor();
  b.ensureColor();
  a.color()[0] = glm::vec4(100.0f / 255.0f, 0.0f, 0.0f, 1.0f);
  b.color()[0] = glm::vec4(101.0f / 255.0f, 0.0f, 0.0f, 1.0f);  // one 8-bit step brighter
  writePng(a, dir.file("a.png"));
  writePng(b, dir.file("b.png"));
  CompareResult exact = compareImages(dir.file("a.png"), dir.file("b.png"), Tolerances{});
  CHECK(exact.failedPixels == 1);
  REQUIRE(exact.channels.size() == 3);
  CHECK(exact.channels[0].maxAbsDiff == Approx(1.0 / 255.0).margin(1e-9));
  Tolerances oneStep;
  oneStep.fallback = 1.0 / 255.0 + 1e-9;
  CHECK(compareImages(dir.file("a.png"), dir.file("b.png"), oneStep).passed);
}

TEST_CASE("a file that cannot be read is an error, not a failed comparison", "[image]") {
  TempDir dir("compare-missing");
  writeExr(makeFramebuffer(), dir.file("a.exr"));
  CHECK_THROWS_AS(compareImages(dir.file("a.exr"), dir.file("nope.exr"), Tolerances{}), std::runtime_error);
}

TEST_CASE("a framebuffer matches its own EXR golden and a changed pixel is found", "[image]") {
  TempDir dir("compare-golden");
  Framebuffer fb = makeFramebuffer();
  writeExr(fb, dir.file("golden.exr"));
  CHECK(compareWithExr(fb, dir.file("golden.exr")).passed);

  SECTION("colour within 1/255 passes") {
    fb.color()[fb.index(1, 1)].r += 0.003f;
    CHECK(compareWithExr(fb, dir.file("golden.exr")).passed);
  }
  SECTION("depth is compared exactly") {
    fb.depthCodes()[fb.index(3, 2)] += 1;  // one ulp of float depth
    CompareResult r = compareWithExr(fb, dir.file("golden.exr"));
    CHECK_FALSE(r.passed);
    REQUIRE(r.firstFailures.size() == 1);
    CHECK(r.firstFailures[0].x == 3);
    CHECK(r.firstFailures[0].y == 0);
    CHECK(r.firstFailures[0].glY == 2);
    CHECK(r.firstFailures[0].failingChannels == std::vector<std::string>{"Z"});
  }
  SECTION("stencil is compared exactly") {
    fb.stencil()[fb.index(0, 0)] += 1;
    CompareResult r = compareWithExr(fb, dir.file("golden.exr"));
    CHECK(r.failedPixels == 1);
    CHECK(r.nameA == "framebuffer");
  }
  SECTION("a framebuffer without stencil does not match a golden with stencil") {
    Framebuffer noStencil(4, 3);
    noStencil.ensureColor();
    noStencil.ensureDepth();
    CompareResult r = compareWithExr(noStencil, dir.file("golden.exr"));
    CHECK_FALSE(r.passed);
    CHECK(r.structuralError == "channel sets differ: only in A: (none); only in B: stencil");
  }
}

TEST_CASE("a golden with per-light stencil channels is compared with the same extras", "[image]") {
  TempDir dir("compare-golden-extras");
  Framebuffer fb = makeFramebuffer();
  ExrExtras extras;
  extras.channels.push_back(NamedChannel::stencilChannel("stencil.L0", std::vector<uint8_t>(12, 1)));
  extras.channels.push_back(NamedChannel::stencilChannel("stencil.L1", std::vector<uint8_t>(12, 2)));
  writeExr(fb, dir.file("golden.exr"), extras);
  CHECK(compareWithExr(fb, extras, dir.file("golden.exr")).passed);
  CHECK(compareWithExr(fb, dir.file("golden.exr")).structuralError ==
        "channel sets differ: only in A: (none); only in B: stencil.L0, stencil.L1");
  extras.channels[1].uints[11] = 3;  // framebuffer (3, 2): the top-right pixel, file row 0
  CompareResult r = compareWithExr(fb, extras, dir.file("golden.exr"));
  REQUIRE(r.firstFailures.size() == 1);
  CHECK(r.firstFailures[0].x == 3);
  CHECK(r.firstFailures[0].y == 0);
  CHECK(r.firstFailures[0].failingChannels == std::vector<std::string>{"stencil.L1"});
}

TEST_CASE("readChannelImage refuses more channel values than its limit, before reading pixels", "[image][hostile]") {
  TempDir dir("compare-limit");
  const std::string path = dir.file("fb.exr");
  writeExr(makeFramebuffer(), path);  // 4x3 with R, G, B, A, Z, stencil: 72 values
  ReadLimits exact;
  exact.maxValues = 72;
  CHECK(readChannelImage(path, exact).data.size() == 6);  // the limit itself is allowed
  ReadLimits tight;
  tight.maxValues = 71;
  try {
    readChannelImage(path, tight);
    FAIL("no exception");
  } catch (const std::runtime_error& e) {
    CHECK(containsText(e.what(), "cannot read '" + path + "'"));
    CHECK(containsText(e.what(), "4x3 pixels with 6 channels, more than the limit of 71 channel values"));
  }
}

TEST_CASE("readChannelImage refuses an uncompressed EXR cut short, from its size alone", "[image][hostile]") {
  // Uncompressed, the pixel bytes are in the file one to one: a file shorter than them is refused
  // by the size check, before OpenImageIO is asked for a single pixel.
  TempDir dir("compare-cut");
  const std::string path = dir.file("fb.exr");
  {
    OIIO::ImageSpec spec(64, 64, 4, OIIO::TypeDesc::FLOAT);
    spec.attribute("compression", "none");
    std::vector<float> pixels(64 * 64 * 4, 0.5f);
    auto out = OIIO::ImageOutput::create(path);
    REQUIRE(out);
    REQUIRE(out->open(path, spec));
    REQUIRE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
    REQUIRE(out->close());
  }
  CHECK(readChannelImage(path).width == 64);
  const auto full = std::filesystem::file_size(path);
  REQUIRE(full > 64 * 64 * 4 * 4);
  std::filesystem::resize_file(path, full - 64 * 64 * 4 * 4 / 2);  // half the pixel bytes gone
  try {
    readChannelImage(path);
    FAIL("no exception");
  } catch (const std::runtime_error& e) {
    CHECK(containsText(e.what(), "(65536 bytes of pixels), more than its"));
  }
}
