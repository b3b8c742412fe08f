#include <cstdint>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include <catch2/catch.hpp>

#include "image/channel_image.h"
#include "image/exr_header_check.h"
#include "image/image_writer.h"
#include "image/temp_dir.h"

using namespace shadowref;
using shadowref::test::TempDir;

namespace {

std::string u32(std::uint32_t v) {
  return std::string{char(v & 0xff), char((v >> 8) & 0xff), char((v >> 16) & 0xff), char((v >> 24) & 0xff)};
}

std::string attribute(const std::string& name, const std::string& type, std::int32_t declared, size_t actual) {
  return name + '\0' + type + '\0' + u32(std::uint32_t(declared)) + std::string(actual, 'x');
}

const std::string kMagic = std::string{char(0x76), char(0x2f), char(0x31), char(0x01)};

}  // namespace

TEST_CASE("an EXR header whose attributes fit in the file passes the walk", "[image][hostile]") {
  const std::string file = kMagic + u32(2) + attribute("compression", "compression", 1, 1) +
                           attribute("comment", "string", 5, 5) + '\0' + std::string(16, 'p');
  CHECK(checkExrHeaders(file).empty());
  // Multi-part: two headers, then the empty header that ends the list.
  const std::string multi = kMagic + u32(2 | 0x1000) + attribute("name", "string", 1, 1) + '\0' +
                            attribute("name", "string", 1, 1) + '\0' + '\0';
  CHECK(checkExrHeaders(multi).empty());
}

TEST_CASE("an EXR attribute declaring more bytes than the file holds is refused by name", "[image][hostile]") {
  // The fuzzer's case: a few hundred bytes declaring a 1.85 GB attribute.
  const std::string header = kMagic + u32(2) + attribute("comment", "string", 1850000000, 3);
  const size_t left = header.size() - (4 + 4 + 8 + 7 + 4);
  CHECK(checkExrHeaders(header) == "attribute 'comment' declares 1850000000 bytes, more than the " +
                                       std::to_string(left) + " left in the file");
  CHECK(checkExrHeaders(kMagic + u32(2) + attribute("a", "int", -1, 0)) ==
        "attribute 'a' declares -1 bytes, more than the 0 left in the file");
  // Exactly the bytes left is allowed; one more is not.
  CHECK(checkExrHeaders(kMagic + u32(2) + attribute("a", "int", 4, 4)) == "a header attribute's name is not terminated");
  CHECK(checkExrHeaders(kMagic + u32(2) + attribute("a", "int", 5, 4)) ==
        "attribute 'a' declares 5 bytes, more than the 4 left in the file");
}

TEST_CASE("an EXR header cut short or with over-long names is refused", "[image][hostile]") {
  CHECK(checkExrHeaders(kMagic) == "the file ends inside its version field");
  CHECK(checkExrHeaders(kMagic + u32(2) + "comment") == "a header attribute's name is not terminated");
  CHECK(checkExrHeaders(kMagic + u32(2) + std::string("c\0", 2) + "str") == "attribute 'c' has no type name");
  CHECK(checkExrHeaders(kMagic + u32(2) + std::string("c\0int\0", 6) + "ab") == "attribute 'c' has no size");
  // 32 bytes of name: too long unless the version field allows long names.
  const std::string longName(32, 'n');
  CHECK_FALSE(checkExrHeaders(kMagic + u32(2) + attribute(longName, "int", 0, 0) + '\0').empty());
  CHECK(checkExrHeaders(kMagic + u32(2 | 0x400) + attribute(longName, "int", 0, 0) + '\0').empty());
  CHECK(checkExrHeaders(kMagic + u32(2 | 0x1000) + attribute("a", "int", 0, 0) + '\0') ==
        "the file ends inside its headers");
}

TEST_CASE("shadowref's own EXRs pass the header walk, and the hostile one is refused before OpenEXR", "[image][hostile]") {
  TempDir dir("exr-header");
  const std::string path = dir.file("fb.exr");
  Framebuffer fb(4, 3);
  fb.ensureColor();
  fb.ensureDepth();
  fb.ensureStencil();
  writeExr(fb, path);
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(looksLikeExr(bytes));
  CHECK(checkExrHeaders(bytes).empty());
  CHECK(readChannelImage(path).width == 4);

  const std::string hostile = std::string(SHADOWREF_SOURCE_DIR) + "/tests/data/hostile/images/exr_huge_attribute.exr";
  try {
    readChannelImage(hostile);
    FAIL("no exception");
  } catch (const std::runtime_error& e) {
    CHECK_THAT(e.what(), Catch::Matchers::Contains("declares") && Catch::Matchers::Contains("left in the file"));
  }
}

TEST_CASE("readChannelImage reads only regular files within its size limit", "[image][hostile]") {
  CHECK_THROWS_WITH(readChannelImage("/dev/zero"), Catch::Matchers::Contains("not a regular file"));
  TempDir dir("exr-size");
  const std::string path = dir.file("fb.exr");
  Framebuffer fb(2, 2);
  fb.ensureColor();
  writeExr(fb, path);
  ReadLimits small;
  small.maxFileBytes = 10;
  CHECK_THROWS_WITH(readChannelImage(path, small), Catch::Matchers::Contains("bytes, more than the limit of 10"));
}
