#include "image/output_metadata.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <stdexcept>

#include <nettle/sha1.h>

namespace shadowref {

std::vector<std::pair<std::string, std::string>> metadataAttributes(const OutputMetadata& metadata) {
  std::vector<std::pair<std::string, std::string>> attributes;
  if (metadata.empty()) return attributes;
  std::string overrides;
  for (const std::string& o : metadata.overrides) overrides += (overrides.empty() ? "-D " : " -D ") + shellWord(o);
  attributes.emplace_back("Software", metadata.software);
  attributes.emplace_back("ImageDescription",
                          metadata.content + " of " + metadata.scene + ", shadow method " + metadata.method);
  attributes.emplace_back("shadowref:content", metadata.content);
  attributes.emplace_back("shadowref:method", metadata.method);
  attributes.emplace_back("shadowref:scene", metadata.scene);
  if (!metadata.sceneSha1.empty()) attributes.emplace_back("shadowref:scene-sha1", metadata.sceneSha1);
  // Only when there are some: OpenImageIO reads an empty PNG text chunk as no attribute, so an
  // empty value would read differently from the two formats.
  if (!overrides.empty()) attributes.emplace_back("shadowref:overrides", overrides);
  attributes.emplace_back("shadowref:threads", std::to_string(metadata.threads));
  attributes.emplace_back("shadowref:pipeline", metadata.pipeline);
  for (const auto& attribute : metadata.extra) attributes.push_back(attribute);
  return attributes;
}

std::string sha1OfFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read '" + path + "' to hash it");
  sha1_ctx sha1;
  sha1_init(&sha1);
  char buffer[1 << 16];
  while (in) {
    in.read(buffer, sizeof buffer);
    if (in.gcount() > 0) sha1_update(&sha1, size_t(in.gcount()), reinterpret_cast<const uint8_t*>(buffer));
  }
  if (in.bad()) throw std::runtime_error("cannot read '" + path + "' to hash it");
  uint8_t digest[SHA1_DIGEST_SIZE];
  sha1_digest(&sha1, SHA1_DIGEST_SIZE, digest);
  static constexpr char kHex[] = "0123456789abcdef";
  std::string hex;
  for (const uint8_t byte : digest) {
    hex += kHex[byte >> 4];
    hex += kHex[byte & 15];
  }
  return hex;
}

std::string shellWord(const std::string& word) {
  const bool plain = !word.empty() && std::all_of(word.begin(), word.end(), [](unsigned char c) {
    return std::isalnum(c) || c == '_' || c == '.' || c == '=' || c == ',' || c == ':' || c == '/' || c == '+' ||
           c == '-' || c == '@' || c == '%';
  });
  if (plain) return word;
  std::string quoted = "'";
  for (char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

}  // namespace shadowref
