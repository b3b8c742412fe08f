#include <cstdint>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include <catch2/catch.hpp>

#include "image/channel_image.h"
#include "image/exr_header_check.h"
#include "image/png_chunk_check.h"
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
  CHECK_FALSE(checkExrHeaders(kMagic + u32(2) + attribute(longName, "string", 0, 0) + '\0').empty());
  CHECK(checkExrHeaders(kMagic + u32(2 | 0x400) + attribute(longName, "string", 0, 0) + '\0').empty());
  CHECK(checkExrHeaders(kMagic + u32(2 | 0x1000) + attribute("a", "string", 0, 0) + '\0') ==
        "the file ends inside its headers");
}

namespace {

std::string value(const std::string& name, const std::string& type, const std::string& bytes) {
  return name + '\0' + type + '\0' + u32(std::uint32_t(bytes.size())) + bytes;
}

std::string box2i(std::int32_t x0, std::int32_t y0, std::int32_t x1, std::int32_t y1) {
  return u32(std::uint32_t(x0)) + u32(std::uint32_t(y0)) + u32(std::uint32_t(x1)) + u32(std::uint32_t(y1));
}

// One channel entry: name\0, pixel type, pLinear + 3 reserved bytes, x and y sampling.
std::string channel(const std::string& name) { return name + '\0' + u32(1) + u32(0) + u32(1) + u32(1); }

}  // namespace

TEST_CASE("an EXR attribute of a known type must have the size OpenEXR reads it with", "[image][hostile]") {
  const std::string head = kMagic + u32(2);
  CHECK(checkExrHeaders(head + value("a", "int", u32(7)) + '\0').empty());
  CHECK(checkExrHeaders(head + value("a", "int", u32(7) + u32(0)) + '\0') ==
        "attribute 'a' of type int declares 8 bytes; the type holds 4");
  CHECK(checkExrHeaders(head + value("w", "box2i", u32(0)) + '\0') ==
        "attribute 'w' of type box2i declares 4 bytes; the type holds 16");
  // Unknown types are opaque to OpenEXR and read by their size.
  CHECK(checkExrHeaders(head + value("x", "myType", "abc") + '\0').empty());
  CHECK(checkExrHeaders(head + value("v", "floatvector", "abcdef") + '\0') ==
        "attribute 'v' of type floatvector is not a whole number of floats");
}

TEST_CASE("an EXR channel list, string vector or preview must end where its size says", "[image][hostile]") {
  const std::string head = kMagic + u32(2);
  const std::string channels = channel("R") + channel("G") + '\0';
  CHECK(checkExrHeaders(head + value("channels", "chlist", channels) + '\0').empty());
  // The list's end marker missing: OpenEXR would read on past the declared size.
  CHECK(checkExrHeaders(head + value("channels", "chlist", channel("R") + channel("G")) + '\0') ==
        "attribute 'channels' of type chlist does not end where its size says");
  // The list ending before its size: OpenEXR would take the rest for the next attribute.
  CHECK_FALSE(checkExrHeaders(head + value("channels", "chlist", channels + "zz") + '\0').empty());
  CHECK(checkExrHeaders(head + value("s", "stringvector", u32(2) + "ab" + u32(0)) + '\0').empty());
  CHECK(checkExrHeaders(head + value("s", "stringvector", u32(2) + "ab" + u32(9) + "c") + '\0') ==
        "attribute 's' of type stringvector does not end where its size says");
  CHECK(checkExrHeaders(head + value("p", "preview", u32(1) + u32(2) + std::string(8, 'x')) + '\0').empty());
  CHECK(checkExrHeaders(head + value("p", "preview", u32(65536) + u32(65536) + std::string(8, 'x')) + '\0') ==
        "attribute 'p' of type preview does not end where its size says");
}

TEST_CASE("an EXR whose chunk offset table would not fit in the file is refused", "[image][hostile]") {
  const std::string head = kMagic + u32(2);
  const std::string none = value("compression", "compression", std::string(1, '\0'));
  // 16 scan lines uncompressed: 16 chunks, 128 bytes of offsets, more than this 75-byte header.
  const std::string small = head + none + value("dataWindow", "box2i", box2i(0, 0, 3, 15)) + '\0';
  REQUIRE(small.size() == 75);
  CHECK(checkExrHeaders(small) == "the header's data window needs 16 chunks, more than its 75-byte file can index");
  // The same with zip (16 lines a chunk): one chunk fits.
  const std::string zip = value("compression", "compression", std::string(1, '\3'));
  CHECK(checkExrHeaders(head + zip + value("dataWindow", "box2i", box2i(0, 0, 3, 15)) + '\0').empty());
  // A data window of 2^31 rows in a few dozen bytes.
  CHECK_FALSE(
      checkExrHeaders(head + none + value("dataWindow", "box2i", box2i(0, -1073741824, 0, 1073741823)) + '\0').empty());
  // Tiled: 1x1 tiles over 16x16 pixels are 256 chunks.
  const std::string tiled = kMagic + u32(2 | 0x200) + value("dataWindow", "box2i", box2i(0, 0, 15, 15)) +
                            value("tiles", "tiledesc", u32(1) + u32(1) + std::string(1, '\0')) + '\0';
  CHECK_THAT(checkExrHeaders(tiled), Catch::Matchers::Contains("needs 16 x 16 tiles"));
  const std::string tiles4 = kMagic + u32(2 | 0x200) + value("dataWindow", "box2i", box2i(0, 0, 15, 15)) +
                             value("tiles", "tiledesc", u32(8) + u32(8) + std::string(1, '\0')) + '\0';
  CHECK(checkExrHeaders(tiles4).empty());
  CHECK_THAT(checkExrHeaders(kMagic + u32(2 | 0x1000) + value("chunkCount", "int", u32(1000000)) + '\0' + '\0'),
             Catch::Matchers::Contains("declares 1000000 chunks"));
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
  // The fuzzer's case: a channel list without its end marker, after which OpenEXR read a 2 GB
  // size from inside the next attribute.
  const std::string overrun = std::string(SHADOWREF_SOURCE_DIR) + "/tests/data/hostile/images/exr_channel_list_overrun.exr";
  CHECK_THROWS_WITH(readChannelImage(overrun), Catch::Matchers::Contains("does not end where its size says"));
}

TEST_CASE("PNG chunks are walked before libpng: a chunk longer than the file is refused", "[image][hostile]") {
  const std::string signature("\x89PNG\r\n\x1a\n", 8);
  // IHDR of 13 bytes with its CRC (not checked by the walk), then IEND: whole.
  const std::string ihdr = std::string("\0\0\0\x0dIHDR", 8) + std::string(13, '\1') + "crc!";
  const std::string iend = std::string("\0\0\0\0IEND", 8) + "crc!";
  CHECK(looksLikePng(signature + ihdr));
  CHECK_FALSE(looksLikePng("\x89PNX"));
  CHECK(checkPngChunks(signature + ihdr + iend).empty());
  // A text chunk declaring 0x40000000 bytes in a file of 57.
  const std::string text = std::string("\x40\0\0\0tEXt", 8) + "x";
  CHECK(checkPngChunks(signature + ihdr + text) ==
        "PNG chunk 'tEXt' at byte 33 declares 1073741824 bytes, past the end of the file (42 bytes)");
  CHECK_THAT(checkPngChunks(signature + std::string("\x80\0\0\0IDAT", 8)), Catch::Matchers::Contains("more than PNG allows"));
  // The fuzzer's case: a 216-byte file whose second text chunk declares 1 GB, which libpng allocated.
  const std::string hostile = std::string(SHADOWREF_SOURCE_DIR) + "/tests/data/hostile/images/png_text_chunk_overrun.png";
  CHECK_THROWS_WITH(readChannelImage(hostile), Catch::Matchers::Contains("past the end of the file"));
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
