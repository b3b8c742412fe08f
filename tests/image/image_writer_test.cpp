#include <cmath>
#include <cstdint>
#include <fstream>
#include <stdexcept>

#include <catch2/catch.hpp>
#include <OpenImageIO/imageio.h>

#include "image/atomic_write.h"
#include "image/image_writer.h"
#include "image/temp_dir.h"

using namespace shadowref;
using shadowref::test::TempDir;

namespace {

// A 3x2 framebuffer whose every pixel is distinguishable: colour (x/4, y/2, 0.25, 1 - x/8),
// depth (x + 3y + 1) / 8, stencil 10 * (x + 3y) + 1.
Framebuffer makeFilledFramebuffer(DepthFormat depthFormat = DepthFormat::Float32) {
  Framebuffer fb(3, 2, depthFormat);
  fb.ensureColor();
  fb.ensureDepth();
  fb.ensureStencil();
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) {
      fb.color()[fb.index(x, y)] = glm::vec4(float(x) / 4.0f, float(y) / 2.0f, 0.25f, 1.0f - float(x) / 8.0f);
      fb.depthCodes()[fb.index(x, y)] = fb.depthCodec().encode(double(x + 3 * y + 1) / 8.0);
      fb.stencil()[fb.index(x, y)] = uint8_t(10 * (x + 3 * y) + 1);
    }
  return fb;
}

struct ReadBack {
  OIIO::ImageSpec spec;
  std::vector<std::string> names;
};

ReadBack readSpec(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  REQUIRE(in);
  ReadBack r{in->spec(), {}};
  for (int c = 0; c < r.spec.nchannels; ++c) r.names.push_back(r.spec.channel_name(c));
  in->close();
  return r;
}

int channelOf(const ReadBack& r, const std::string& name) {
  for (size_t c = 0; c < r.names.size(); ++c)
    if (r.names[c] == name) return int(c);
  FAIL("channel " << name << " missing");
  return -1;
}

// One channel of the file, read in its stored 4-byte type (no conversion), top row first.
template <typename T>
std::vector<T> readChannelRaw(const std::string& path, int channel, OIIO::TypeDesc type) {
  auto in = OIIO::ImageInput::open(path);
  REQUIRE(in);
  std::vector<T> values(size_t(in->spec().width) * size_t(in->spec().height));
  REQUIRE(in->read_image(0, 0, channel, channel + 1, type, values.data()));
  in->close();
  return values;
}

bool containsText(const std::string& haystack, const std::string& needle) {
  return haystack.find(needle) != std::string::npos;
}

}  // namespace

TEST_CASE("EXR holds R G B A and Z as FLOAT and stencil as UINT32", "[image]") {
  TempDir dir("exr-formats");
  const std::string path = dir.file("fb.exr");
  writeExr(makeFilledFramebuffer(), path);
  ReadBack r = readSpec(path);
  CHECK(r.spec.width == 3);
  CHECK(r.spec.height == 2);
  REQUIRE(r.spec.nchannels == 6);
  std::vector<std::string> sorted = r.names;
  std::sort(sorted.begin(), sorted.end());
  CHECK(sorted == std::vector<std::string>{"A", "B", "G", "R", "Z", "stencil"});
  for (const char* c : {"R", "G", "B", "A", "Z"}) CHECK(r.spec.channelformat(channelOf(r, c)) == OIIO::TypeDesc::FLOAT);
  CHECK(r.spec.channelformat(channelOf(r, "stencil")) == OIIO::TypeDesc::UINT32);
}

TEST_CASE("EXR values are exact and framebuffer row 0 is the last scanline of the file", "[image]") {
  TempDir dir("exr-values");
  const std::string path = dir.file("fb.exr");
  writeExr(makeFilledFramebuffer(), path);
  ReadBack r = readSpec(path);
  auto stencil = readChannelRaw<uint32_t>(path, channelOf(r, "stencil"), OIIO::TypeDesc::UINT32);
  auto z = readChannelRaw<float>(path, channelOf(r, "Z"), OIIO::TypeDesc::FLOAT);
  auto red = readChannelRaw<float>(path, channelOf(r, "R"), OIIO::TypeDesc::FLOAT);
  auto green = readChannelRaw<float>(path, channelOf(r, "G"), OIIO::TypeDesc::FLOAT);
  auto alpha = readChannelRaw<float>(path, channelOf(r, "A"), OIIO::TypeDesc::FLOAT);
  // File row 1 (the last scanline) is framebuffer row 0; file row 0 is framebuffer row 1.
  CHECK(stencil == std::vector<uint32_t>{31, 41, 51, 1, 11, 21});
  CHECK(z == std::vector<float>{4 / 8.f, 5 / 8.f, 6 / 8.f, 1 / 8.f, 2 / 8.f, 3 / 8.f});
  CHECK(red == std::vector<float>{0.f, 0.25f, 0.5f, 0.f, 0.25f, 0.5f});
  CHECK(green == std::vector<float>{0.5f, 0.5f, 0.5f, 0.f, 0.f, 0.f});
  CHECK(alpha == std::vector<float>{1.f, 0.875f, 0.75f, 1.f, 0.875f, 0.75f});
}

TEST_CASE("EXR compressions: RLE by default, each lossless and named in the header", "[image]") {
  TempDir dir("exr-compression");
  struct Restore {
    ~Restore() { setExrCompression(kDefaultExrCompression); }
  } restore;
  CHECK(kDefaultExrCompression == ExrCompression::Rle);
  CHECK_FALSE(exrCompressionNamed("lzw").has_value());
  const Framebuffer fb = makeFilledFramebuffer();
  writeExr(fb, dir.file("default.exr"));
  CHECK(readSpec(dir.file("default.exr")).spec.get_string_attribute("compression") == "rle");
  for (const char* name : {"none", "rle", "zip"}) {
    INFO(name);
    setExrCompression(*exrCompressionNamed(name));
    const std::string path = dir.file(std::string(name) + ".exr");
    writeExr(fb, path);
    ReadBack r = readSpec(path);
    CHECK(r.spec.get_string_attribute("compression") == name);
    CHECK(readChannelRaw<uint32_t>(path, channelOf(r, "stencil"), OIIO::TypeDesc::UINT32) ==
          std::vector<uint32_t>{31, 41, 51, 1, 11, 21});
    CHECK(readChannelRaw<float>(path, channelOf(r, "Z"), OIIO::TypeDesc::FLOAT) ==
          std::vector<float>{4 / 8.f, 5 / 8.f, 6 / 8.f, 1 / 8.f, 2 / 8.f, 3 / 8.f});
  }
}

TEST_CASE("EXR carries no time stamp, so the same framebuffer gives the same bytes", "[image]") {
  TempDir dir("exr-no-date");
  writeExr(makeFilledFramebuffer(), dir.file("a.exr"));
  CHECK(readSpec(dir.file("a.exr")).spec.find_attribute("DateTime") == nullptr);
  writeExr(makeFilledFramebuffer(), dir.file("b.exr"));
  std::ifstream a(dir.file("a.exr"), std::ios::binary), b(dir.file("b.exr"), std::ios::binary);
  CHECK(std::string(std::istreambuf_iterator<char>(a), {}) == std::string(std::istreambuf_iterator<char>(b), {}));
}

TEST_CASE("EXR Z of a 24-bit depth buffer is the decoded window depth code / (2^24 - 1)", "[image]") {
  TempDir dir("exr-unorm24");
  const std::string path = dir.file("fb.exr");
  Framebuffer fb(1, 1, DepthFormat::Unorm24);
  fb.ensureDepth();
  fb.depthCodes()[0] = 8388608;  // 2^23
  writeExr(fb, path);
  ReadBack r = readSpec(path);
  REQUIRE(r.names == std::vector<std::string>{"Z"});
  auto z = readChannelRaw<float>(path, 0, OIIO::TypeDesc::FLOAT);
  CHECK(z[0] == float(8388608.0 / 16777215.0));
}

TEST_CASE("EXR writes only the buffers the framebuffer has", "[image]") {
  TempDir dir("exr-only-existing");
  Framebuffer fb(2, 2);
  fb.ensureStencil();
  fb.stencil()[fb.index(1, 0)] = 255;
  const std::string path = dir.file("stencil-only.exr");
  writeExr(fb, path);
  ReadBack r = readSpec(path);
  REQUIRE(r.names == std::vector<std::string>{"stencil"});
  CHECK(readChannelRaw<uint32_t>(path, 0, OIIO::TypeDesc::UINT32) == std::vector<uint32_t>{0, 0, 0, 255});

  Framebuffer empty(2, 2);
  CHECK_THROWS_AS(writeExr(empty, dir.file("empty.exr")), std::invalid_argument);
  CHECK(dir.entries() == std::vector<std::string>{"stencil-only.exr"});
}

TEST_CASE("per-light stencil channels: one per light, named stencil.<light>, only for several lights", "[image]") {
  std::vector<PixelVector<uint8_t>> stencils(2);
  stencils[0].assign({1, 2, 255});
  stencils[1].assign({0, 7, 3});
  const std::vector<std::string> names{"L0", "L1"};
  const ExrExtras two = perLightStencilChannels(stencils, names);
  REQUIRE(two.channels.size() == 2);
  CHECK(two.channels[0].name == "stencil.L0");
  CHECK(two.channels[1].name == "stencil.L1");
  CHECK(two.channels[0].kind == ChannelKind::UInt32);
  CHECK(two.channels[0].uints == std::vector<uint32_t>{1, 2, 255});
  CHECK(two.channels[1].uints == std::vector<uint32_t>{0, 7, 3});
  // One light: its counts are the framebuffer's own stencil channel, nothing extra.
  CHECK(perLightStencilChannels(std::span(stencils.data(), 1), std::span(names.data(), 1)).channels.empty());
}

TEST_CASE("EXR extras add per-light stencil channels as UINT32 and float channels as FLOAT", "[image]") {
  TempDir dir("exr-extras");
  Framebuffer fb(2, 1);
  fb.ensureStencil();
  ExrExtras extras;
  extras.channels.push_back(NamedChannel::stencilChannel("stencil.L0", std::vector<uint8_t>{3, 4}));
  extras.channels.push_back(NamedChannel::uintChannel("stencil.L1", {300, 70000}));
  extras.channels.push_back(NamedChannel::floatChannel("shadow", {0.4f, 1.0f}));
  const std::string path = dir.file("extras.exr");
  writeExr(fb, path, extras);
  ReadBack r = readSpec(path);
  REQUIRE(r.spec.nchannels == 4);
  CHECK(r.spec.channelformat(channelOf(r, "stencil.L0")) == OIIO::TypeDesc::UINT32);
  CHECK(r.spec.channelformat(channelOf(r, "stencil.L1")) == OIIO::TypeDesc::UINT32);
  CHECK(r.spec.channelformat(channelOf(r, "shadow")) == OIIO::TypeDesc::FLOAT);
  CHECK(readChannelRaw<uint32_t>(path, channelOf(r, "stencil.L0"), OIIO::TypeDesc::UINT32) == std::vector<uint32_t>{3, 4});
  CHECK(readChannelRaw<uint32_t>(path, channelOf(r, "stencil.L1"), OIIO::TypeDesc::UINT32) ==
        std::vector<uint32_t>{300, 70000});
  CHECK(readChannelRaw<float>(path, channelOf(r, "shadow"), OIIO::TypeDesc::FLOAT) == std::vector<float>{0.4f, 1.0f});
}

TEST_CASE("EXR extras of the wrong size or with a taken name are rejected before writing", "[image]") {
  TempDir dir("exr-bad-extras");
  Framebuffer fb(2, 1);
  fb.ensureStencil();
  ExrExtras wrongSize;
  wrongSize.channels.push_back(NamedChannel::floatChannel("x", {1.0f}));
  CHECK_THROWS_AS(writeExr(fb, dir.file("a.exr"), wrongSize), std::invalid_argument);
  ExrExtras taken;
  taken.channels.push_back(NamedChannel::uintChannel("stencil", {1, 2}));
  CHECK_THROWS_AS(writeExr(fb, dir.file("b.exr"), taken), std::invalid_argument);
  CHECK(dir.entries().empty());
}

TEST_CASE("PNG is 8-bit RGB with round(c * 255) and the top row first", "[image]") {
  TempDir dir("png");
  Framebuffer fb(2, 2);
  fb.ensureColor();
  fb.color()[fb.index(0, 0)] = glm::vec4(0.5f, 0.25f, 0.75f, 1.0f);  // 127.5, 63.75, 191.25
  fb.color()[fb.index(1, 0)] = glm::vec4(1.0f, 0.0f, 128.0f / 255.0f, 0.0f);
  fb.color()[fb.index(0, 1)] = glm::vec4(0.498f, 0.002f, 0.001f, 0.5f);  // 126.99, 0.51, 0.255
  fb.color()[fb.index(1, 1)] = glm::vec4(0.0f);
  const std::string path = dir.file("c.png");
  writePng(fb, path);
  auto in = OIIO::ImageInput::open(path);
  REQUIRE(in);
  CHECK(in->spec().nchannels == 3);
  CHECK(in->spec().format == OIIO::TypeDesc::UINT8);
  std::vector<uint8_t> px(12);
  REQUIRE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, px.data()));
  // File row 0 = framebuffer row 1.
  CHECK(px == std::vector<uint8_t>{127, 1, 0, 0, 0, 0, 128, 64, 191, 255, 0, 128});
}

TEST_CASE("PNG with alpha adds the A channel", "[image]") {
  TempDir dir("png-alpha");
  Framebuffer fb(1, 1);
  fb.ensureColor();
  fb.color()[0] = glm::vec4(0.0f, 0.0f, 0.0f, 0.5f);
  writePng(fb, dir.file("a.png"), true);
  auto in = OIIO::ImageInput::open(dir.file("a.png"));
  REQUIRE(in);
  REQUIRE(in->spec().nchannels == 4);
  std::vector<uint8_t> px(4);
  REQUIRE(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::UINT8, px.data()));
  CHECK(px == std::vector<uint8_t>{0, 0, 0, 128});
}

TEST_CASE("writeImage chooses the format by extension and rejects others", "[image]") {
  TempDir dir("write-image");
  Framebuffer fb = makeFilledFramebuffer();
  writeImage(fb, dir.file("a.PNG"));
  writeImage(fb, dir.file("b.exr"));
  CHECK(readSpec(dir.file("a.PNG")).spec.nchannels == 3);
  CHECK(readSpec(dir.file("b.exr")).spec.nchannels == 6);
  try {
    writeImage(fb, dir.file("c.tif"));
    FAIL("no exception");
  } catch (const std::invalid_argument& e) {
    CHECK(containsText(e.what(), "'.tif'"));
    CHECK(containsText(e.what(), ".png"));
    CHECK(containsText(e.what(), ".exr"));
  }
  CHECK_THROWS_AS(writeImage(fb, dir.file("noextension")), std::invalid_argument);
  CHECK(dir.entries() == std::vector<std::string>{"a.PNG", "b.exr"});
}

TEST_CASE("a write into a missing directory throws and leaves no file", "[image]") {
  TempDir dir("atomic-missing");
  Framebuffer fb = makeFilledFramebuffer();
  const std::string path = dir.file("missing/out.exr");
  try {
    writeExr(fb, path);
    FAIL("no exception");
  } catch (const std::runtime_error& e) {
    CHECK(containsText(e.what(), path));
  }
  CHECK(dir.entries().empty());
}

TEST_CASE("a write below a regular file throws and leaves no file", "[image]") {
  // A path whose directory is a file is unwritable even for root (chmod would not stop root).
  TempDir dir("atomic-notdir");
  std::ofstream(dir.file("plain")) << "x";
  CHECK_THROWS_AS(writePng(makeFilledFramebuffer(), dir.file("plain/out.png")), std::runtime_error);
  CHECK(dir.entries() == std::vector<std::string>{"plain"});
}

TEST_CASE("a failed rename removes the finished temporary file", "[image]") {
  // The target is a non-empty directory: the image is written completely, then cannot replace it.
  TempDir dir("atomic-rename");
  std::filesystem::create_directories(dir.path() / "out.exr" / "inside");
  CHECK_THROWS_AS(writeExr(makeFilledFramebuffer(), dir.file("out.exr")), std::runtime_error);
  CHECK(dir.entries() == std::vector<std::string>{"out.exr"});
  CHECK(std::filesystem::is_directory(dir.path() / "out.exr"));
}

TEST_CASE("a writer that fails half-way leaves the old file untouched and no temporary file", "[image]") {
  TempDir dir("atomic-old");
  const std::string path = dir.file("keep.txt");
  std::ofstream(path) << "old";
  CHECK_THROWS_AS(writeFileAtomically(path,
                                      [](const TempFile& temp) {
                                        writeAllAt(temp.fd, "half", 4, 0);
                                        throw std::runtime_error("disk full");
                                      }),
                  std::runtime_error);
  CHECK(dir.entries() == std::vector<std::string>{"keep.txt"});
  std::ifstream in(path);
  std::string content;
  in >> content;
  CHECK(content == "old");
}

TEST_CASE("a successful write replaces an existing file", "[image]") {
  TempDir dir("atomic-replace");
  const std::string path = dir.file("fb.png");
  std::ofstream(path) << "not a png";
  writePng(makeFilledFramebuffer(), path);
  CHECK(readSpec(path).spec.width == 3);
  CHECK(dir.entries() == std::vector<std::string>{"fb.png"});
}

TEST_CASE("grey PNG maps lo to 0 and hi to 255, flips rows, and clamps", "[image]") {
  Image8 g = greyImage({0.0f, 0.5f, 1.0f, 2.0f, -1.0f, NAN}, 3, 2, 0.0f, 1.0f);
  CHECK(g.channels == 1);
  // Framebuffer row 1 (2, -1, NaN) comes first.
  CHECK(g.pixels == std::vector<uint8_t>{255, 0, 0, 0, 128, 255});
  Image8 shifted = greyImage({0.25f, 0.75f}, 2, 1, 0.25f, 0.75f);
  CHECK(shifted.pixels == std::vector<uint8_t>{0, 255});
  CHECK_THROWS_AS(greyImage({0.0f}, 1, 1, 1.0f, 1.0f), std::invalid_argument);
  CHECK_THROWS_AS(greyImage({0.0f}, 2, 1, 0.0f, 1.0f), std::invalid_argument);

  TempDir dir("grey");
  writeGreyPng({0.0f, 0.5f, 1.0f, 2.0f, -1.0f, NAN}, 3, 2, dir.file("g.png"), 0.0f, 1.0f);
  auto in = OIIO::ImageInput::open(dir.file("g.png"));
  REQUIRE(in);
  CHECK(in->spec().nchannels == 1);
  std::vector<uint8_t> px(6);
  REQUIRE(in->read_image(0, 0, 0, 1, OIIO::TypeDesc::UINT8, px.data()));
  CHECK(px == g.pixels);
}
