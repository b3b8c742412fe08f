#include "image/exr_header_check.h"

#include <cstddef>
#include <iterator>
#include <optional>
#include <string>

namespace shadowref {

namespace {

constexpr unsigned char kMagic[4] = {0x76, 0x2f, 0x31, 0x01};
// Version field flags (OpenEXR file layout, "Version Field"): tiles, long attribute names (up to
// 255 bytes instead of 31) and several parts, each with its own header, the list ended by an
// empty one.
constexpr std::uint32_t kTiled = 0x200;
constexpr std::uint32_t kLongNames = 0x400;
constexpr std::uint32_t kMultiPart = 0x1000;
// OpenEXR reads channel names and attribute names of up to 255 bytes whatever the flag says.
constexpr size_t kMaxChannelName = 255;

std::uint32_t readU32(std::string_view bytes, size_t at) {
  return std::uint32_t(static_cast<unsigned char>(bytes[at])) |
         std::uint32_t(static_cast<unsigned char>(bytes[at + 1])) << 8 |
         std::uint32_t(static_cast<unsigned char>(bytes[at + 2])) << 16 |
         std::uint32_t(static_cast<unsigned char>(bytes[at + 3])) << 24;
}

std::int32_t readI32(std::string_view bytes, size_t at) { return static_cast<std::int32_t>(readU32(bytes, at)); }

// Reads a NUL-terminated string of at most `maxLength` bytes at `at`; advances `at` past the NUL.
// Returns false when there is no NUL in time.
bool readName(std::string_view bytes, size_t& at, size_t maxLength, std::string_view& name) {
  const size_t end = bytes.find('\0', at);
  if (end == std::string_view::npos || end - at > maxLength) return false;
  name = bytes.substr(at, end - at);
  at = end + 1;
  return true;
}

// The bytes OpenEXR's reader of a known fixed-size type consumes, whatever size the attribute
// declares; nullopt for the types read by their declared size or by their own structure.
std::optional<size_t> fixedSize(std::string_view type) {
  struct Entry {
    std::string_view type;
    size_t bytes;
  };
  static constexpr Entry kFixed[] = {
      {"box2i", 16},  {"box2f", 16},    {"chromaticities", 32}, {"compression", 1}, {"double", 8},
      {"envmap", 1},  {"float", 4},     {"int", 4},             {"keycode", 28},    {"lineOrder", 1},
      {"m33f", 36},   {"m33d", 72},     {"m44f", 64},           {"m44d", 128},      {"rational", 8},
      {"tiledesc", 9}, {"timecode", 8}, {"v2i", 8},             {"v2f", 8},         {"v2d", 16},
      {"v3i", 12},    {"v3f", 12},      {"v3d", 24},            {"deepImageState", 1}};
  for (const Entry& e : kFixed)
    if (e.type == type) return e.bytes;
  return std::nullopt;
}

// A channel list: entries of name\0 and 16 bytes (type, pLinear, 3 reserved, x and y sampling),
// ended by an empty name. OpenEXR reads it by this structure, not by the declared size, so the
// structure must end exactly where the size says.
bool channelListEndsAtItsSize(std::string_view value) {
  size_t at = 0;
  for (;;) {
    std::string_view name;
    if (!readName(value, at, kMaxChannelName, name)) return false;
    if (name.empty()) return at == value.size();
    if (value.size() - at < 16) return false;
    at += 16;
  }
}

// A string vector: int32 length, then that many bytes, until the declared size is used up.
bool stringVectorEndsAtItsSize(std::string_view value) {
  size_t at = 0;
  while (at < value.size()) {
    if (value.size() - at < 4) return false;
    const std::int32_t length = readI32(value, at);
    at += 4;
    if (length < 0 || size_t(length) > value.size() - at) return false;
    at += size_t(length);
  }
  return true;
}

// A preview image: uint32 width and height, then width x height RGBA bytes.
bool previewEndsAtItsSize(std::string_view value) {
  if (value.size() < 8) return false;
  const std::uint64_t pixels = std::uint64_t(readU32(value, 0)) * std::uint64_t(readU32(value, 4));
  return pixels <= (std::uint64_t(1) << 40) && pixels * 4 == value.size() - 8;
}

// "" when OpenEXR's reader of `type` consumes exactly the declared bytes `value`, so that the next
// attribute starts where this walk expects it; otherwise what is wrong.
std::string checkValue(std::string_view name, std::string_view type, std::string_view value) {
  const std::string what = "attribute '" + std::string(name) + "' of type " + std::string(type);
  if (const std::optional<size_t> bytes = fixedSize(type)) {
    if (value.size() != *bytes)
      return what + " declares " + std::to_string(value.size()) + " bytes; the type holds " + std::to_string(*bytes);
    return "";
  }
  if (type == "chlist" && !channelListEndsAtItsSize(value)) return what + " does not end where its size says";
  if (type == "stringvector" && !stringVectorEndsAtItsSize(value)) return what + " does not end where its size says";
  if (type == "preview" && !previewEndsAtItsSize(value)) return what + " does not end where its size says";
  if (type == "floatvector" && value.size() % 4 != 0) return what + " is not a whole number of floats";
  if (type == "idmanifest" && value.size() < 4) return what + " is shorter than its 4-byte length field";
  return "";
}

// What one header says about the size of its chunk offset table.
struct PartLayout {
  std::optional<std::int64_t> width, height;  // of the data window
  std::optional<unsigned> compression;
  std::optional<std::uint32_t> tileWidth, tileHeight;
  std::optional<std::int32_t> chunkCount;
  bool tiled = false;
};

void note(PartLayout& part, std::string_view name, std::string_view type, std::string_view value) {
  if (name == "dataWindow" && type == "box2i") {
    part.width = std::int64_t(readI32(value, 8)) - readI32(value, 0) + 1;
    part.height = std::int64_t(readI32(value, 12)) - readI32(value, 4) + 1;
  } else if (name == "compression" && type == "compression") {
    part.compression = static_cast<unsigned char>(value[0]);
  } else if (name == "tiles" && type == "tiledesc") {
    part.tileWidth = readU32(value, 0);
    part.tileHeight = readU32(value, 4);
  } else if (name == "chunkCount" && type == "int") {
    part.chunkCount = readI32(value, 0);
  } else if (name == "type" && type == "string") {
    if (value == "tiledimage" || value == "deeptile") part.tiled = true;
  }
}

// Scan lines per chunk for each compression (OpenEXR file layout, "Compression"); zip when the
// header names none, as OpenEXR's default header does.
std::int64_t linesPerChunk(std::optional<unsigned> compression) {
  static constexpr std::int64_t kLines[] = {1, 1, 1, 16, 32, 16, 32, 32, 32, 256};
  const unsigned c = compression.value_or(3);
  return c < std::size(kLines) ? kLines[c] : 1;
}

// OpenEXR allocates one 8-byte offset per chunk before reading any pixel: a file cannot hold fewer
// bytes than its offset table, so a header whose chunks need more is refused.
std::string checkOffsetTable(const PartLayout& part, size_t fileBytes) {
  const std::int64_t maxChunks = std::int64_t(fileBytes / 8);
  if (part.chunkCount && (*part.chunkCount < 0 || *part.chunkCount > maxChunks))
    return "the header declares " + std::to_string(*part.chunkCount) + " chunks, more than its " +
           std::to_string(fileBytes) + "-byte file can index";
  if (!part.width || !part.height || *part.width <= 0 || *part.height <= 0) return "";  // OpenEXR refuses it
  std::int64_t chunks;
  if (part.tiled && part.tileWidth && part.tileHeight) {
    if (*part.tileWidth == 0 || *part.tileHeight == 0) return "";  // OpenEXR refuses it
    const std::int64_t across = (*part.width + *part.tileWidth - 1) / *part.tileWidth;
    const std::int64_t down = (*part.height + *part.tileHeight - 1) / *part.tileHeight;
    if (across > maxChunks / down)  // also where across * down would not fit in 64 bits
      return "the header's data window needs " + std::to_string(across) + " x " + std::to_string(down) +
             " tiles, more than its " + std::to_string(fileBytes) + "-byte file can index";
    chunks = across * down;
  } else {
    const std::int64_t lines = linesPerChunk(part.compression);
    chunks = (*part.height + lines - 1) / lines;
  }
  if (chunks > maxChunks)
    return "the header's data window needs " + std::to_string(chunks) + " chunks, more than its " +
           std::to_string(fileBytes) + "-byte file can index";
  return "";
}

// Walks one header's attributes from `at` to its terminating NUL. "" or what is wrong.
std::string walkHeader(std::string_view bytes, size_t& at, size_t maxName, PartLayout& part) {
  for (;;) {
    std::string_view name, type;
    if (!readName(bytes, at, maxName, name)) return "a header attribute's name is not terminated";
    if (name.empty()) return "";  // the header's end
    if (!readName(bytes, at, maxName, type)) return "attribute '" + std::string(name) + "' has no type name";
    if (bytes.size() - at < 4) return "attribute '" + std::string(name) + "' has no size";
    const std::int32_t size = readI32(bytes, at);
    at += 4;
    const size_t left = bytes.size() - at;
    if (size < 0 || size_t(size) > left)
      return "attribute '" + std::string(name) + "' declares " + std::to_string(size) + " bytes, more than the " +
             std::to_string(left) + " left in the file";
    const std::string_view value = bytes.substr(at, size_t(size));
    if (std::string problem = checkValue(name, type, value); !problem.empty()) return problem;
    note(part, name, type, value);
    at += size_t(size);
  }
}

}  // namespace

bool looksLikeExr(std::string_view bytes) {
  if (bytes.size() < 4) return false;
  for (size_t i = 0; i < 4; ++i)
    if (static_cast<unsigned char>(bytes[i]) != kMagic[i]) return false;
  return true;
}

std::string checkExrHeaders(std::string_view bytes) {
  if (!looksLikeExr(bytes)) return "not an OpenEXR file";
  if (bytes.size() < 8) return "the file ends inside its version field";
  const std::uint32_t version = readU32(bytes, 4);
  const size_t maxName = (version & kLongNames) ? 255 : 31;
  size_t at = 8;
  auto walkPart = [&]() -> std::string {
    PartLayout part;
    part.tiled = (version & kTiled) != 0;
    if (std::string problem = walkHeader(bytes, at, maxName, part); !problem.empty()) return problem;
    return checkOffsetTable(part, bytes.size());
  };
  if (!(version & kMultiPart)) return walkPart();
  // Multi-part: headers follow one another; an empty header (a lone NUL) ends the list.
  for (;;) {
    if (at >= bytes.size()) return "the file ends inside its headers";
    if (bytes[at] == '\0') return "";
    if (std::string problem = walkPart(); !problem.empty()) return problem;
  }
}

}  // namespace shadowref
