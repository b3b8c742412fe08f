#include "image/exr_header_check.h"

#include <cstddef>

namespace shadowref {

namespace {

constexpr unsigned char kMagic[4] = {0x76, 0x2f, 0x31, 0x01};
// Version field flags (OpenEXR file layout, "Version Field"): long attribute names (up to 255
// bytes instead of 31) and several parts, each with its own header, the list ended by an empty one.
constexpr std::uint32_t kLongNames = 0x400;
constexpr std::uint32_t kMultiPart = 0x1000;

std::uint32_t readU32(std::string_view bytes, size_t at) {
  return std::uint32_t(static_cast<unsigned char>(bytes[at])) |
         std::uint32_t(static_cast<unsigned char>(bytes[at + 1])) << 8 |
         std::uint32_t(static_cast<unsigned char>(bytes[at + 2])) << 16 |
         std::uint32_t(static_cast<unsigned char>(bytes[at + 3])) << 24;
}

// Reads a NUL-terminated string of at most `maxLength` bytes at `at`; advances `at` past the NUL.
// Returns false when there is no NUL in time.
bool readName(std::string_view bytes, size_t& at, size_t maxLength, std::string_view& name) {
  const size_t end = bytes.find('\0', at);
  if (end == std::string_view::npos || end - at > maxLength) return false;
  name = bytes.substr(at, end - at);
  at = end + 1;
  return true;
}

// Walks one header's attributes from `at` to its terminating NUL. "" or what is wrong.
std::string walkHeader(std::string_view bytes, size_t& at, size_t maxName) {
  for (;;) {
    std::string_view name, type;
    if (!readName(bytes, at, maxName, name)) return "a header attribute's name is not terminated";
    if (name.empty()) return "";  // the header's end
    if (!readName(bytes, at, maxName, type)) return "attribute '" + std::string(name) + "' has no type name";
    if (bytes.size() - at < 4) return "attribute '" + std::string(name) + "' has no size";
    const std::int32_t size = static_cast<std::int32_t>(readU32(bytes, at));
    at += 4;
    const size_t left = bytes.size() - at;
    if (size < 0 || size_t(size) > left)
      return "attribute '" + std::string(name) + "' declares " + std::to_string(size) + " bytes, more than the " +
             std::to_string(left) + " left in the file";
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
  if (!(version & kMultiPart)) return walkHeader(bytes, at, maxName);
  // Multi-part: headers follow one another; an empty header (a lone NUL) ends the list.
  for (;;) {
    if (at >= bytes.size()) return "the file ends inside its headers";
    if (bytes[at] == '\0') return "";
    if (std::string problem = walkHeader(bytes, at, maxName); !problem.empty()) return problem;
  }
}

}  // namespace shadowref
