// The provenance written into images: its attributes in both formats, the scene hash, the quoting
// of the -D overrides, and that it changes no pixel and no byte between equal writes.
#include <fstream>
#include <string>

#include <catch2/catch.hpp>
#include <OpenImageIO/imageio.h>

#include "image/image_writer.h"
#include "image/output_metadata.h"
#include "image/temp_dir.h"

using namespace shadowref;
using shadowref::test::TempDir;

namespace {

OutputMetadata sampleMetadata() {
  OutputMetadata m;
  m.software = "shadowref 9.8.7 (0123abc)";
  m.content = "frame";
  m.method = "zfail";
  m.scene = "scenes/some room.yaml";
  m.sceneSha1 = "a9993e364706816aba3e25717850c26c9cd0d89d";
  m.overrides = {"image.width=64", "ambient=[0.5, 0.5, 0.5]", "lights.0.name=it's"};
  m.threads = 3;
  m.pipeline = "fast";
  return m;
}

Framebuffer smallFramebuffer() {
  Framebuffer fb(2, 2, DepthFormat::Float32);
  fb.ensureColor();
  fb.ensureDepth();
  for (size_t i = 0; i < 4; ++i) fb.color()[i] = glm::vec4(0.25f * float(i), 0.5f, 1.0f, 1.0f);
  return fb;
}

OIIO::ImageSpec readSpec(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  REQUIRE(in);
  OIIO::ImageSpec spec = in->spec();
  in->close();
  return spec;
}

std::string bytesOf(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void writeFile(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

}  // namespace

TEST_CASE("sha1OfFile gives the FIPS 180 digests, across its read buffer", "[image][metadata]") {
  TempDir dir("sha1");
  // FIPS 180-2 appendix A test vectors; one million 'a' spans several 64 KiB reads.
  writeFile(dir.file("empty"), "");
  writeFile(dir.file("abc"), "abc");
  writeFile(dir.file("million"), std::string(1000000, 'a'));
  CHECK(sha1OfFile(dir.file("empty")) == "da39a3ee5e6b4b0d3255bfef95601890afd80709");
  CHECK(sha1OfFile(dir.file("abc")) == "a9993e364706816aba3e25717850c26c9cd0d89d");
  CHECK(sha1OfFile(dir.file("million")) == "34aa973cd4c4daa4f61eeb2bdbad27316534016f");
  CHECK_THROWS_AS(sha1OfFile(dir.file("missing")), std::runtime_error);
}

TEST_CASE("shellWord leaves plain words alone and single-quotes the rest", "[image][metadata]") {
  CHECK(shellWord("camera.near=0.001") == "camera.near=0.001");
  CHECK(shellWord("ambient=[1, 0, 0]") == "'ambient=[1, 0, 0]'");
  CHECK(shellWord("name=it's") == "'name=it'\\''s'");
  CHECK(shellWord("a=$HOME") == "'a=$HOME'");
  CHECK(shellWord("") == "''");
}

TEST_CASE("metadata attributes: every field in order, none for empty metadata", "[image][metadata]") {
  CHECK(metadataAttributes(OutputMetadata{}).empty());
  const auto attributes = metadataAttributes(sampleMetadata());
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"Software", "shadowref 9.8.7 (0123abc)"},
      {"ImageDescription", "frame of scenes/some room.yaml, shadow method zfail"},
      {"shadowref:content", "frame"},
      {"shadowref:method", "zfail"},
      {"shadowref:scene", "scenes/some room.yaml"},
      {"shadowref:scene-sha1", "a9993e364706816aba3e25717850c26c9cd0d89d"},
      {"shadowref:overrides", "-D image.width=64 -D 'ambient=[0.5, 0.5, 0.5]' -D 'lights.0.name=it'\\''s'"},
      {"shadowref:threads", "3"},
      {"shadowref:pipeline", "fast"},
  };
  CHECK(attributes == expected);
  OutputMetadata builtIn = sampleMetadata();
  builtIn.sceneSha1.clear();
  builtIn.overrides.clear();
  std::vector<std::string> names;
  for (const auto& [name, value] : metadataAttributes(builtIn)) names.push_back(name);
  CHECK(names == std::vector<std::string>{"Software", "ImageDescription", "shadowref:content", "shadowref:method",
                                          "shadowref:scene", "shadowref:threads", "shadowref:pipeline"});
}

TEST_CASE("EXR and PNG carry the metadata, read back by OpenImageIO, with unchanged pixels", "[image][metadata]") {
  TempDir dir("metadata");
  const OutputMetadata m = sampleMetadata();
  const Framebuffer fb = smallFramebuffer();
  for (const char* name : {"a.exr", "a.png"}) {
    INFO(name);
    writeImage(fb, dir.file(name), m);
    const OIIO::ImageSpec spec = readSpec(dir.file(name));
    for (const auto& [key, value] : metadataAttributes(m)) {
      INFO(key);
      CHECK(spec.get_string_attribute(key) == value);
    }
  }
  // The pixels are those of a file without metadata.
  writeImage(fb, dir.file("plain.png"));
  writeImage(fb, dir.file("plain.exr"));
  CHECK(readSpec(dir.file("plain.png")).get_string_attribute("shadowref:method").empty());
  for (const char* ext : {".png", ".exr"}) {
    auto with = OIIO::ImageInput::open(dir.file(std::string("a") + ext));
    auto without = OIIO::ImageInput::open(dir.file(std::string("plain") + ext));
    REQUIRE(with);
    REQUIRE(without);
    std::vector<float> a(size_t(with->spec().image_pixels()) * size_t(with->spec().nchannels));
    std::vector<float> b(a.size());
    REQUIRE(with->read_image(0, 0, 0, -1, OIIO::TypeDesc::FLOAT, a.data()));
    REQUIRE(without->read_image(0, 0, 0, -1, OIIO::TypeDesc::FLOAT, b.data()));
    CHECK(a == b);
  }
  // The same metadata gives the same bytes: nothing in it depends on the time of writing.
  writeImage(fb, dir.file("b.exr"), m);
  writeImage(fb, dir.file("b.png"), m);
  CHECK(bytesOf(dir.file("a.exr")) == bytesOf(dir.file("b.exr")));
  CHECK(bytesOf(dir.file("a.png")) == bytesOf(dir.file("b.png")));
}

TEST_CASE("extra attributes follow the others in order and read back from EXR and PNG", "[image][metadata]") {
  TempDir dir("metadata-extra");
  OutputMetadata m = sampleMetadata();
  m.extra = {{"shadowref:visibility.L0", "sun"}, {"shadowref:visibility.L1", "the lamp's"}};
  const auto attributes = metadataAttributes(m);
  REQUIRE(attributes.size() == 11);
  CHECK(attributes[8] == std::pair<std::string, std::string>{"shadowref:pipeline", "fast"});
  CHECK(attributes[9] == std::pair<std::string, std::string>{"shadowref:visibility.L0", "sun"});
  CHECK(attributes[10] == std::pair<std::string, std::string>{"shadowref:visibility.L1", "the lamp's"});
  for (const char* name : {"v.exr", "v.png"}) {
    INFO(name);
    writeImage(smallFramebuffer(), dir.file(name), m);
    const OIIO::ImageSpec spec = readSpec(dir.file(name));
    CHECK(spec.get_string_attribute("shadowref:visibility.L0") == "sun");
    CHECK(spec.get_string_attribute("shadowref:visibility.L1") == "the lamp's");
  }
}
