#include "image/png_chunk_check.h"

#include <cstdint>

namespace shadowref {

namespace {

constexpr std::string_view kSignature("\x89PNG\r\n\x1a\n", 8);

std::uint32_t bigEndian32(std::string_view bytes, size_t at) {
  std::uint32_t v = 0;
  for (size_t k = 0; k < 4; ++k) v = (v << 8) | static_cast<unsigned char>(bytes[at + k]);
  return v;
}

}  // namespace

bool looksLikePng(std::string_view bytes) { return bytes.substr(0, kSignature.size()) == kSignature; }

std::string checkPngChunks(std::string_view bytes) {
  size_t at = kSignature.size();
  while (bytes.size() - at >= 8) {  // a chunk's length and type
    const std::uint32_t length = bigEndian32(bytes, at);
    const std::string type(bytes.substr(at + 4, 4));
    if (length > 0x7fffffffu)
      return "PNG chunk '" + type + "' at byte " + std::to_string(at) + " declares " + std::to_string(length) +
             " bytes, more than PNG allows (2^31 - 1)";
    const std::uint64_t end = std::uint64_t(at) + 12 + length;  // length, type, data, CRC
    if (end > bytes.size())
      return "PNG chunk '" + type + "' at byte " + std::to_string(at) + " declares " + std::to_string(length) +
             " bytes, past the end of the file (" + std::to_string(bytes.size()) + " bytes)";
    if (type == "IEND") return "";
    at = size_t(end);
  }
  return "";
}

}  // namespace shadowref
