// glTF 2.0 and its binary container .glb. tinygltf builds the model, but it is handed only input
// we have checked ourselves, because it trusts its input in several places (a .glb chunk length,
// the size of a "file" that is a folder, an image's buffer view): the .glb layout, the JSON
// syntax and nesting, the types of every property we read, and the external buffer files (regular,
// size-limited, of the declared length) are checked first, and everything the renderer does not
// use (images, materials, animations, ...) is dropped from the JSON before tinygltf sees it.
// Every error is located by our own knowledge: a JSON pointer we built, mapped to its place in the
// text (line:column in a .gltf, the byte offset in a .glb) -- never by reading a message.
#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string_view>

#include <sys/stat.h>

// tinygltf: this is the one translation unit that compiles its implementation. Images are not
// needed for geometry, so none of the image code is built or run.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include "scene/checked_arithmetic.h"
#include "scene/input_file.h"
#include "scene/mesh_import.h"
#include "scene/scene_error.h"

namespace shadowref {

namespace {

using Json = nlohmann::json;
using Pointer = std::vector<std::string>;  // a JSON pointer, one token per level

// tinygltf reads nested JSON (extras) recursively: the nesting limit keeps its stack bounded, the
// value limit the memory of the two JSON trees (ours and tinygltf's).
constexpr int kMaxJsonDepth = 64;
constexpr size_t kMaxJsonValues = 4'000'000;
constexpr uint64_t kMaxJsonBytes = uint64_t{64} << 20;
constexpr int kMaxNodeDepth = 256;
constexpr size_t kMaxGltfVertices = 3 * kMaxGltfTriangles;

uint32_t readU32(const std::string& bytes, size_t at) {
  const auto* b = reinterpret_cast<const unsigned char*>(bytes.data()) + at;
  return uint32_t{b[0]} | uint32_t{b[1]} << 8 | uint32_t{b[2]} << 16 | uint32_t{b[3]} << 24;
}

void appendU32(std::string& out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
}

// The file's JSON text and how to name a place in it.
class GltfSource {
 public:
  GltfSource(const std::string& path, bool binary) : path_(path), binary_(binary) {
    bytes_ = readInputFile(path, "mesh file");
    if (binary_) {
      splitGlb();
    } else {
      if (bytes_.size() > kMaxJsonBytes) fail(0, "the JSON has more than " + std::to_string(kMaxJsonBytes) + " bytes");
      json_ = bytes_;
    }
  }

  const std::string& path() const { return path_; }
  bool binary() const { return binary_; }
  std::string_view json() const { return json_; }
  std::string_view bin() const { return bin_; }

  // At a byte offset into the JSON text: line and column in a .gltf, the file offset in a .glb.
  [[noreturn]] void fail(size_t jsonOffset, const std::string& message) const {
    if (binary_) failAtByte(jsonStart_ + jsonOffset, message);
    int line = 1, column = 1;
    const size_t end = std::min(jsonOffset, json_.size());
    for (size_t i = 0; i < end; ++i) {
      if (json_[i] == '\n') ++line, column = 1;
      else ++column;
    }
    throw SceneError(SourceLocation{path_, line, column}, message);
  }
  [[noreturn]] void fail(const Pointer& where, const std::string& message) const {
    fail(find(where), message);
  }
  [[noreturn]] void failAtByte(size_t fileOffset, const std::string& message) const {
    throw SceneError(SourceLocation{path_, 0, 0}, "at byte " + std::to_string(fileOffset) + ": " + message);
  }

  // Where the value `where` starts in the JSON text; for a member or element that is not written
  // (a default), where its nearest written ancestor starts. The text has been parsed already, so
  // it is well-formed and nested at most kMaxJsonDepth deep.
  size_t find(const Pointer& where) const {
    const std::string_view s = json_;
    size_t i = skipSpace(0);
    for (const std::string& token : where) {
      if (i >= s.size()) break;
      const size_t found = s[i] == '{' ? member(i, token) : s[i] == '[' ? element(i, token) : std::string_view::npos;
      if (found == std::string_view::npos) break;
      i = found;
    }
    return i;
  }

 private:
  size_t skipSpace(size_t i) const {
    while (i < json_.size() && (json_[i] == ' ' || json_[i] == '\t' || json_[i] == '\n' || json_[i] == '\r')) ++i;
    return i;
  }
  size_t skipString(size_t i) const {  // json_[i] == '"'
    for (++i; i < json_.size(); ++i) {
      if (json_[i] == '\\') ++i;
      else if (json_[i] == '"') return i + 1;
    }
    return json_.size();
  }
  size_t skipValue(size_t i) const {
    if (i >= json_.size()) return i;
    if (json_[i] == '"') return skipString(i);
    if (json_[i] == '{' || json_[i] == '[') {
      int depth = 0;
      while (i < json_.size()) {
        const char c = json_[i];
        if (c == '"') {
          i = skipString(i);
          continue;
        }
        if (c == '{' || c == '[') ++depth;
        if ((c == '}' || c == ']') && --depth == 0) return i + 1;
        ++i;
      }
      return i;
    }
    while (i < json_.size() && std::strchr(",]} \t\r\n", json_[i]) == nullptr) ++i;
    return i;
  }
  size_t member(size_t i, const std::string& key) const {  // json_[i] == '{'
    i = skipSpace(i + 1);
    while (i < json_.size() && json_[i] == '"') {
      const size_t keyEnd = skipString(i);
      const std::string_view written = json_.substr(i + 1, keyEnd - i - 2);
      i = skipSpace(keyEnd);
      if (i < json_.size() && json_[i] == ':') i = skipSpace(i + 1);
      if (written == key) return i;
      i = skipSpace(skipValue(i));
      if (i < json_.size() && json_[i] == ',') i = skipSpace(i + 1);
    }
    return std::string_view::npos;
  }
  size_t element(size_t i, const std::string& token) const {  // json_[i] == '['
    size_t index = 0;
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), index);
    if (ec != std::errc() || end != token.data() + token.size()) return std::string_view::npos;
    i = skipSpace(i + 1);
    for (size_t k = 0; i < json_.size() && json_[i] != ']'; ++k) {
      if (k == index) return i;
      i = skipSpace(skipValue(i));
      if (i < json_.size() && json_[i] == ',') i = skipSpace(i + 1);
    }
    return std::string_view::npos;
  }

  // The .glb layout (glTF 2.0 §4.4): a 12-byte header, a JSON chunk, then an optional BIN chunk;
  // chunks of other types are skipped. Every length is checked against the file before use.
  void splitGlb() {
    const uint64_t size = bytes_.size();
    if (size < 12) failAtByte(0, "too short for the 12-byte .glb header");
    if (bytes_.compare(0, 4, "glTF") != 0) failAtByte(0, "not a binary glTF file (the magic is not 'glTF')");
    if (const uint32_t version = readU32(bytes_, 4); version != 2)
      failAtByte(4, ".glb version " + std::to_string(version) + " is not supported (2 only)");
    if (const uint32_t length = readU32(bytes_, 8); length != size)
      failAtByte(8, "the header says the file has " + std::to_string(length) + " bytes, it has " + std::to_string(size));
    uint64_t at = 12;
    bool haveJson = false, haveBin = false;
    while (at < size) {
      if (!rangeInside(at, 8, size)) failAtByte(at, "chunk header reaches past the end of the file");
      const uint32_t length = readU32(bytes_, at), type = readU32(bytes_, at + 4);
      if (!rangeInside(at + 8, length, size))
        failAtByte(at, "chunk of " + std::to_string(length) + " bytes reaches past the end of the file");
      if (length % 4 != 0) failAtByte(at, "chunk length " + std::to_string(length) + " is not a multiple of 4");
      if (!haveJson) {
        if (type != 0x4E4F534Au) failAtByte(at + 4, "the first chunk is not of type JSON");
        if (length > kMaxJsonBytes)
          failAtByte(at, "the JSON chunk has more than " + std::to_string(kMaxJsonBytes) + " bytes");
        jsonStart_ = at + 8;
        json_ = std::string_view(bytes_).substr(at + 8, length);
        haveJson = true;
      } else if (type == 0x004E4942u) {
        if (haveBin) failAtByte(at, "a second BIN chunk");
        bin_ = std::string_view(bytes_).substr(at + 8, length);
        haveBin = true;
      }
      at += 8 + uint64_t{length};
    }
    if (!haveJson) failAtByte(12, "no JSON chunk");
  }

  std::string path_;
  bool binary_;
  std::string bytes_;
  std::string_view json_, bin_;
  size_t jsonStart_ = 0;
};

// Nesting depth and value count, before any tree is built.
void checkJsonShape(const GltfSource& source) {
  const std::string_view s = source.json();
  int depth = 0;
  size_t values = 1;
  for (size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if (c == '"') {
      for (++i; i < s.size() && s[i] != '"'; ++i)
        if (s[i] == '\\') ++i;
    } else if (c == '{' || c == '[') {
      if (++depth > kMaxJsonDepth) source.fail(i, "JSON nested more than " + std::to_string(kMaxJsonDepth) + " deep");
    } else if (c == '}' || c == ']') {
      --depth;
    } else if (c == ',' && ++values > kMaxJsonValues) {
      source.fail(i, "more than " + std::to_string(kMaxJsonValues) + " JSON values");
    }
  }
}

Json parseJson(const GltfSource& source) {
  checkJsonShape(source);
  const std::string_view s = source.json();
  try {
    return Json::parse(s.begin(), s.end());
  } catch (const Json::parse_error& e) {
    // e.byte counts from 1 and points just past the character that broke the syntax.
    const size_t at = e.byte > 0 ? std::min<size_t>(e.byte - 1, s.size()) : 0;
    if (at >= s.size()) source.fail(at, "JSON ends too early");
    const auto c = static_cast<unsigned char>(s[at]);
    source.fail(at, c >= 0x20 && c < 0x7f ? std::string("JSON syntax error at '") + s[at] + "'"
                                          : "JSON syntax error (an invalid byte " + std::to_string(c) + ")");
  }
}

// The properties we read, checked for presence and type so that tinygltf cannot fail on them
// without a location, and so that its int fields cannot be handed values they do not hold.
class Schema {
 public:
  explicit Schema(const GltfSource& source) : source_(source) {}

  void check(const Json& root) {
    if (!root.is_object()) source_.fail(Pointer{}, "a glTF file is a JSON object");
    const Json* asset = field(root, {}, "asset", true);
    if (!asset->is_object()) source_.fail({"asset"}, "asset: expected an object");
    const Json* version = field(*asset, {"asset"}, "version", true);
    if (!version->is_string() || version->get_ref<const std::string&>().rfind("2.", 0) != 0)
      source_.fail({"asset", "version"}, "asset.version: only glTF 2.x is supported");
    index(root, {}, "scene", false);
    each(root, "scenes", [&](const Json& o, const Pointer& at) { indexList(o, at, "nodes"); });
    each(root, "nodes", [&](const Json& o, const Pointer& at) {
      index(o, at, "mesh", false);
      indexList(o, at, "children");
      numbers(o, at, "matrix", 16);
      numbers(o, at, "translation", 3);
      numbers(o, at, "rotation", 4);
      numbers(o, at, "scale", 3);
    });
    each(root, "meshes", [&](const Json& o, const Pointer& at) {
      const Json* primitives = field(o, at, "primitives", true);
      objectList(*primitives, with(at, "primitives"), [&](const Json& p, const Pointer& pat) {
        const Json* attributes = field(p, pat, "attributes", true);
        const Pointer aat = with(pat, "attributes");
        if (!attributes->is_object()) source_.fail(aat, "attributes: expected an object");
        for (const auto& [name, value] : attributes->items()) index(*attributes, aat, name, true);
        index(p, pat, "indices", false);
        index(p, pat, "mode", false);
      });
    });
    each(root, "accessors", [&](const Json& o, const Pointer& at) {
      index(o, at, "bufferView", false);
      size(o, at, "byteOffset", false);
      index(o, at, "componentType", true);
      const uint64_t componentType = o["componentType"].get<uint64_t>();
      if (componentType < TINYGLTF_COMPONENT_TYPE_BYTE || componentType > TINYGLTF_COMPONENT_TYPE_DOUBLE)
        source_.fail(with(at, "componentType"), "componentType " + std::to_string(componentType) + " is not one of glTF's");
      size(o, at, "count", true);
      const Json* type = field(o, at, "type", true);
      static const std::vector<std::string> kTypes{"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"};
      if (!type->is_string() || std::find(kTypes.begin(), kTypes.end(), type->get_ref<const std::string&>()) == kTypes.end())
        source_.fail(with(at, "type"), "type: expected one of SCALAR, VEC2, VEC3, VEC4, MAT2, MAT3, MAT4");
      if (o.contains("sparse")) source_.fail(with(at, "sparse"), "sparse accessors are not supported");
    });
    each(root, "bufferViews", [&](const Json& o, const Pointer& at) {
      index(o, at, "buffer", true);
      size(o, at, "byteOffset", false);
      size(o, at, "byteLength", true);
      if (size(o, at, "byteLength", true) == 0) source_.fail(with(at, "byteLength"), "byteLength must be at least 1");
      if (o.contains("byteStride")) {
        const uint64_t s = size(o, at, "byteStride", false);
        if (s < 4 || s > 252 || s % 4 != 0)
          source_.fail(with(at, "byteStride"), "byteStride must be a multiple of 4 from 4 to 252");
      }
    });
    each(root, "buffers", [&](const Json& o, const Pointer& at) {
      if (size(o, at, "byteLength", true) == 0) source_.fail(with(at, "byteLength"), "byteLength must be at least 1");
      if (const Json* uri = field(o, at, "uri", false); uri && !uri->is_string())
        source_.fail(with(at, "uri"), "uri: expected text");
    });
  }

  static Pointer with(Pointer p, const std::string& token) {
    p.push_back(token);
    return p;
  }

 private:
  const Json* field(const Json& o, const Pointer& at, const std::string& key, bool required) const {
    const auto it = o.find(key);
    if (it == o.end()) {
      if (required) source_.fail(at, "missing required property '" + key + "'");
      return nullptr;
    }
    return &*it;
  }
  // An index into an array (or an enum): tinygltf keeps these in an int.
  void index(const Json& o, const Pointer& at, const std::string& key, bool required) const {
    const Json* v = field(o, at, key, required);
    if (v && (!v->is_number_unsigned() || v->get<uint64_t>() > uint64_t{std::numeric_limits<int>::max()}))
      source_.fail(with(at, key), key + ": expected an index (an integer from 0 to 2^31 - 1)");
  }
  uint64_t size(const Json& o, const Pointer& at, const std::string& key, bool required) const {
    const Json* v = field(o, at, key, required);
    if (!v) return 0;
    if (!v->is_number_unsigned()) source_.fail(with(at, key), key + ": expected a non-negative integer");
    return v->get<uint64_t>();
  }
  void indexList(const Json& o, const Pointer& at, const std::string& key) const {
    const Json* v = field(o, at, key, false);
    if (!v) return;
    if (!v->is_array()) source_.fail(with(at, key), key + ": expected a list of indices");
    for (size_t i = 0; i < v->size(); ++i) {
      const Json& e = (*v)[i];
      if (!e.is_number_unsigned() || e.get<uint64_t>() > uint64_t{std::numeric_limits<int>::max()})
        source_.fail(with(with(at, key), std::to_string(i)), key + ": expected indices (integers from 0 to 2^31 - 1)");
    }
  }
  void numbers(const Json& o, const Pointer& at, const std::string& key, size_t count) const {
    const Json* v = field(o, at, key, false);
    if (!v) return;
    if (!v->is_array() || v->size() != count)
      source_.fail(with(at, key), key + ": expected a list of " + std::to_string(count) + " numbers");
    for (size_t i = 0; i < count; ++i)
      if (!(*v)[i].is_number()) source_.fail(with(with(at, key), std::to_string(i)), key + ": expected a number");
  }
  template <class F>
  void objectList(const Json& v, const Pointer& at, F&& f) const {
    if (!v.is_array()) source_.fail(at, at.back() + ": expected a list of objects");
    for (size_t i = 0; i < v.size(); ++i) {
      if (!v[i].is_object()) source_.fail(with(at, std::to_string(i)), at.back() + ": expected an object");
      f(v[i], with(at, std::to_string(i)));
    }
  }
  template <class F>
  void each(const Json& root, const std::string& section, F&& f) const {
    if (const auto it = root.find(section); it != root.end()) objectList(*it, {section}, f);
  }
  const GltfSource& source_;
};

// tinygltf's file access: only regular files of bounded size, read whole after the check, never
// written, and no shell-style expansion of the path.
bool fileExists(const std::string& path, void*) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}
std::string expandFilePath(const std::string& path, void*) { return path; }
bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
  try {
    const std::string bytes = readInputFile(path, "buffer file");
    out->assign(bytes.begin(), bytes.end());
    return true;
  } catch (const SceneError& e) {
    if (err) *err += e.message();
    return false;
  }
}
bool writeWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "writing is not allowed";
  return false;
}
// No image is ever decoded (images are dropped from the JSON before tinygltf reads it).
bool skipImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

// External buffer files: found where tinygltf will look first (beside the .gltf), regular, within
// the size limit and exactly as long as declared -- all known before a byte is read.
void checkBuffers(const Json& root, const GltfSource& source) {
  const auto buffers = root.find("buffers");
  if (buffers == root.end()) return;
  const std::filesystem::path base = std::filesystem::path(source.path()).parent_path();
  uint64_t external = 0;
  for (size_t i = 0; i < buffers->size(); ++i) {
    const Json& b = (*buffers)[i];
    const Pointer at{"buffers", std::to_string(i)};
    const uint64_t byteLength = b["byteLength"].get<uint64_t>();
    const auto uri = b.find("uri");
    if (uri == b.end()) {
      if (!source.binary() || i != 0) source.fail(at, "buffer without uri (only the first buffer of a .glb may have none)");
      if (byteLength > source.bin().size())
        source.fail(Schema::with(at, "byteLength"),
                    "byteLength " + std::to_string(byteLength) + " is more than the " +
                        std::to_string(source.bin().size()) + " bytes of the BIN chunk");
      continue;
    }
    const std::string& text = uri->get_ref<const std::string&>();
    if (tinygltf::IsDataURI(text)) {
      // Embedded: bounded by the JSON. Decoded here once to compare the length as tinygltf will.
      std::vector<unsigned char> decoded;
      std::string mime;
      if (!tinygltf::DecodeDataURI(&decoded, mime, text, 0, false))
        source.fail(Schema::with(at, "uri"), "the data URI holds no base64 data");
      if (decoded.size() != byteLength)
        source.fail(Schema::with(at, "uri"), "the data URI holds " + std::to_string(decoded.size()) +
                                                 " bytes, byteLength says " + std::to_string(byteLength));
      continue;
    }
    if (text.rfind("data:", 0) == 0)
      source.fail(Schema::with(at, "uri"), "unsupported data URI (a buffer is data:application/octet-stream;base64,...)");
    const std::string decoded = tinygltf::dlib::urldecode(text);
    const std::string file = base.empty() ? decoded : tinygltf::JoinPath(base.string(), decoded);
    uint64_t size = 0;
    try {
      size = checkInputFile(file, "buffer file");
    } catch (const SceneError& e) {
      source.fail(Schema::with(at, "uri"), "'" + file + "': " + e.message());
    }
    if (size != byteLength)
      source.fail(Schema::with(at, "uri"), "'" + file + "' has " + std::to_string(size) + " bytes, byteLength says " +
                                               std::to_string(byteLength));
    const std::optional<uint64_t> sum = checkedAdd(external, size);
    if (!sum || *sum > kMaxInputFileBytes)
      source.fail(Schema::with(at, "uri"), "the buffer files have more than " + std::to_string(kMaxInputFileBytes) +
                                               " bytes in all");
    external = *sum;
  }
}

// What tinygltf reads: only the sections that hold geometry.
std::string geometryOnly(Json& root) {
  Json kept = Json::object();
  for (const char* key : {"asset", "scene", "scenes", "nodes", "meshes", "accessors", "bufferViews", "buffers"})
    if (const auto it = root.find(key); it != root.end()) kept[key] = std::move(*it);
  root = Json();
  return kept.dump();
}

// A .glb made of our JSON and the file's BIN chunk, padded as the layout requires.
std::string rebuildGlb(std::string json, std::string_view bin, bool haveBin) {
  while (json.size() % 4 != 0) json.push_back(' ');
  std::string binPadded(bin);
  while (binPadded.size() % 4 != 0) binPadded.push_back('\0');
  std::string out = "glTF";
  appendU32(out, 2);
  const uint64_t total = 12 + 8 + json.size() + (haveBin ? 8 + binPadded.size() : 0);
  appendU32(out, static_cast<uint32_t>(total));
  appendU32(out, static_cast<uint32_t>(json.size()));
  appendU32(out, 0x4E4F534Au);
  out += json;
  if (haveBin) {
    appendU32(out, static_cast<uint32_t>(binPadded.size()));
    appendU32(out, 0x004E4942u);
    out += binPadded;
  }
  return out;
}

class GltfReader {
 public:
  GltfReader(const tinygltf::Model& model, const GltfSource& source)
      : model_(model), source_(source), visited_(model.nodes.size(), false) {}

  Mesh read() {
    if (!model_.scenes.empty()) {
      const size_t s = model_.defaultScene >= 0 ? static_cast<size_t>(model_.defaultScene) : 0;
      if (s >= model_.scenes.size()) fail({"scene"}, "default scene " + std::to_string(s) + " does not exist");
      const std::vector<int>& roots = model_.scenes[s].nodes;
      for (size_t k = 0; k < roots.size(); ++k)
        visit(roots[k], glm::dmat4(1.0), 0, {"scenes", std::to_string(s), "nodes", std::to_string(k)});
    } else {
      std::vector<bool> isChild(model_.nodes.size(), false);
      for (const tinygltf::Node& n : model_.nodes)
        for (int c : n.children)
          if (c >= 0 && static_cast<size_t>(c) < isChild.size()) isChild[c] = true;
      for (size_t i = 0; i < model_.nodes.size(); ++i)
        if (!isChild[i]) visit(static_cast<int>(i), glm::dmat4(1.0), 0, {"nodes", std::to_string(i)});
    }
    mesh_.name = std::filesystem::path(source_.path()).stem().string();
    return std::move(mesh_);
  }

  bool haveNormals() const { return haveNormals_; }

 private:
  [[noreturn]] void fail(const Pointer& at, const std::string& message) const { source_.fail(at, message); }
  static std::string str(size_t v) { return std::to_string(v); }

  // `from` is where the index was written (a scene's node list or a parent's children).
  void visit(int index, const glm::dmat4& parent, int depth, const Pointer& from) {
    if (index < 0 || static_cast<size_t>(index) >= model_.nodes.size())
      fail(from, "node " + std::to_string(index) + " does not exist");
    if (depth > kMaxNodeDepth) fail(from, "node hierarchy deeper than " + std::to_string(kMaxNodeDepth));
    // glTF 2.0 §3.5.3: the nodes form disjoint strict trees. A node reached twice would be a cycle
    // or a shared subtree, whose expansion can be exponential in the file's size.
    if (visited_[index])
      fail(from, "node " + std::to_string(index) + " is reached a second time (glTF node hierarchies are strict trees)");
    visited_[index] = true;
    const tinygltf::Node& node = model_.nodes[index];
    const Pointer at{"nodes", std::to_string(index)};
    const glm::dmat4 world = parent * localMatrix(node);
    if (node.mesh >= 0) {
      if (static_cast<size_t>(node.mesh) >= model_.meshes.size())
        fail(Schema::with(at, "mesh"), "mesh " + std::to_string(node.mesh) + " does not exist");
      const auto& primitives = model_.meshes[node.mesh].primitives;
      for (size_t p = 0; p < primitives.size(); ++p)
        addPrimitive(primitives[p], world, {"meshes", std::to_string(node.mesh), "primitives", str(p)}, at);
    }
    for (size_t k = 0; k < node.children.size(); ++k)
      visit(node.children[k], world, depth + 1, Schema::with(Schema::with(at, "children"), str(k)));
  }

  glm::dmat4 localMatrix(const tinygltf::Node& node) const {
    if (node.matrix.size() == 16) {
      glm::dmat4 m;
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) m[c][r] = node.matrix[4 * c + r];  // column-major, as glTF
      return m;
    }
    glm::dmat4 t(1.0), r(1.0), s(1.0);
    if (node.translation.size() == 3)
      t[3] = glm::dvec4(node.translation[0], node.translation[1], node.translation[2], 1.0);
    if (node.rotation.size() == 4) {
      // Quaternion (x, y, z, w) to matrix.
      const double x = node.rotation[0], y = node.rotation[1], z = node.rotation[2], w = node.rotation[3];
      r[0] = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w), 0};
      r[1] = {2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w), 0};
      r[2] = {2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y), 0};
    }
    if (node.scale.size() == 3) {
      s[0][0] = node.scale[0];
      s[1][1] = node.scale[1];
      s[2][2] = node.scale[2];
    }
    return t * r * s;
  }

  // The elements of an accessor, after checking with overflow-safe arithmetic that the buffer view
  // lies inside its buffer and all `count` elements inside the buffer view.
  struct View {
    const unsigned char* data = nullptr;
    size_t stride = 0, count = 0;
    const unsigned char* at(size_t i) const { return data + i * stride; }
  };

  const tinygltf::Accessor& accessor(int index, const Pointer& from, const char* what) const {
    if (index < 0 || static_cast<size_t>(index) >= model_.accessors.size())
      fail(from, std::string(what) + ": accessor " + std::to_string(index) + " does not exist");
    return model_.accessors[index];
  }

  View view(int accessorIndex, int type, std::initializer_list<int> componentTypes, const Pointer& from,
            const char* what) const {
    const tinygltf::Accessor& a = accessor(accessorIndex, from, what);
    const Pointer at{"accessors", std::to_string(accessorIndex)};
    if (a.type != type) fail(Schema::with(at, "type"), std::string(what) + ": accessor has the wrong type");
    bool typeOk = false;
    for (int c : componentTypes) typeOk |= a.componentType == c;
    if (!typeOk) fail(Schema::with(at, "componentType"), std::string(what) + ": unsupported component type");
    if (a.bufferView < 0 || static_cast<size_t>(a.bufferView) >= model_.bufferViews.size())
      fail(Schema::with(at, "bufferView"), std::string(what) + ": accessor has no valid buffer view");
    const tinygltf::BufferView& bv = model_.bufferViews[a.bufferView];
    const Pointer bvAt{"bufferViews", std::to_string(a.bufferView)};
    if (bv.buffer < 0 || static_cast<size_t>(bv.buffer) >= model_.buffers.size())
      fail(Schema::with(bvAt, "buffer"), "buffer " + std::to_string(bv.buffer) + " does not exist");
    const std::vector<unsigned char>& buffer = model_.buffers[bv.buffer].data;
    if (!rangeInside(bv.byteOffset, bv.byteLength, buffer.size()))
      fail(Schema::with(bvAt, "byteLength"), "buffer view reaches outside its buffer of " + str(buffer.size()) + " bytes");
    const uint64_t elementSize =
        uint64_t(tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(a.componentType))) *
        uint64_t(tinygltf::GetNumComponentsInType(static_cast<uint32_t>(a.type)));
    const uint64_t stride = bv.byteStride == 0 ? elementSize : bv.byteStride;
    if (stride < elementSize)
      fail(Schema::with(bvAt, "byteStride"), "byteStride " + str(stride) + " is less than the element's " +
                                                 str(elementSize) + " bytes");
    View v;
    v.stride = stride;
    v.count = a.count;
    if (a.count > 0) {
      const std::optional<uint64_t> span = checkedMulAdd<uint64_t>(a.count - 1, stride, elementSize);
      if (!span || !rangeInside(a.byteOffset, *span, bv.byteLength))
        fail(Schema::with(at, "byteOffset"), std::string(what) + ": accessor reaches outside its buffer view of " +
                                                 str(bv.byteLength) + " bytes");
      v.data = buffer.data() + bv.byteOffset + a.byteOffset;
    }
    return v;
  }

  std::vector<glm::dvec3> readVec3(int accessorIndex, const Pointer& from, const char* what) const {
    const View v = view(accessorIndex, TINYGLTF_TYPE_VEC3, {TINYGLTF_COMPONENT_TYPE_FLOAT}, from, what);
    std::vector<glm::dvec3> out(v.count);
    for (size_t i = 0; i < v.count; ++i) {
      float f[3];
      std::memcpy(f, v.at(i), sizeof f);
      out[i] = {f[0], f[1], f[2]};
    }
    return out;
  }

  std::vector<uint32_t> readIndices(int accessorIndex, const Pointer& from, size_t vertexCount) const {
    const View v = view(accessorIndex, TINYGLTF_TYPE_SCALAR,
                        {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                         TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT},
                        from, "indices");
    const int type = model_.accessors[accessorIndex].componentType;
    std::vector<uint32_t> out(v.count);
    for (size_t i = 0; i < v.count; ++i) {
      if (type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) {
        out[i] = *v.at(i);
      } else if (type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
        uint16_t s;
        std::memcpy(&s, v.at(i), sizeof s);
        out[i] = s;
      } else {
        std::memcpy(&out[i], v.at(i), sizeof out[i]);
      }
      if (out[i] >= vertexCount)
        fail({"accessors", std::to_string(accessorIndex)},
             "index " + std::to_string(out[i]) + " (element " + str(i) + ") is out of range: the primitive has " +
                 str(vertexCount) + " vertices");
    }
    return out;
  }

  void addPrimitive(const tinygltf::Primitive& p, const glm::dmat4& world, const Pointer& at, const Pointer& node) {
    const int mode = p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        mode != TINYGLTF_MODE_TRIANGLE_FAN)
      return;  // points and lines have no surface
    const Pointer attributes = Schema::with(at, "attributes");
    auto position = p.attributes.find("POSITION");
    if (position == p.attributes.end()) fail(attributes, "primitive without POSITION");
    // Budget of the expanded hierarchy (a mesh used by many nodes is copied once per node),
    // checked on the accessors' counts before anything is read.
    const size_t vertexCount = accessor(position->second, Schema::with(attributes, "POSITION"), "POSITION").count;
    const size_t indexCount =
        p.indices >= 0 ? accessor(p.indices, Schema::with(at, "indices"), "indices").count : vertexCount;
    const size_t triangles = mode == TINYGLTF_MODE_TRIANGLES ? indexCount / 3
                             : indexCount >= 3               ? indexCount - 2
                                                             : 0;
    if (triangles > kMaxGltfTriangles - mesh_.triangles.size())
      fail(node, "the node hierarchy holds more than " + str(kMaxGltfTriangles) + " triangles");
    if (vertexCount > kMaxGltfVertices - mesh_.positions.size())
      fail(node, "the node hierarchy holds more than " + str(kMaxGltfVertices) + " vertices");
    const std::vector<glm::dvec3> positions =
        readVec3(position->second, Schema::with(attributes, "POSITION"), "POSITION");
    std::vector<glm::dvec3> normals;
    if (auto normal = p.attributes.find("NORMAL"); normal != p.attributes.end()) {
      normals = readVec3(normal->second, Schema::with(attributes, "NORMAL"), "NORMAL");
      if (normals.size() != positions.size())
        fail(Schema::with(attributes, "NORMAL"), "NORMAL has " + str(normals.size()) + " elements, POSITION " +
                                                     str(positions.size()));
    } else {
      haveNormals_ = false;
    }
    std::vector<uint32_t> indices;
    if (p.indices >= 0) {
      indices = readIndices(p.indices, Schema::with(at, "indices"), positions.size());
    } else {
      indices.resize(positions.size());
      for (uint32_t i = 0; i < indices.size(); ++i) indices[i] = i;
    }
    // A mirroring transform turns the winding around; normals go through the inverse transpose.
    const glm::dmat3 linear(world);
    const bool mirrored = glm::determinant(linear) < 0.0;
    const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(linear));
    const auto base = static_cast<uint32_t>(mesh_.positions.size());
    for (size_t i = 0; i < positions.size(); ++i) {
      mesh_.positions.push_back(glm::dvec3(world * glm::dvec4(positions[i], 1.0)));
      mesh_.normals.push_back(normals.empty() ? glm::dvec3(0.0) : normalMatrix * normals[i]);
    }
    auto emit = [&](uint32_t a, uint32_t b, uint32_t c) {
      if (mirrored) std::swap(b, c);
      mesh_.triangles.push_back(glm::uvec3(base + a, base + b, base + c));
    };
    if (mode == TINYGLTF_MODE_TRIANGLES) {
      for (size_t i = 0; i + 2 < indices.size(); i += 3) emit(indices[i], indices[i + 1], indices[i + 2]);
    } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      for (size_t i = 0; i + 2 < indices.size(); ++i)
        if (i % 2 == 0) emit(indices[i], indices[i + 1], indices[i + 2]);
        else emit(indices[i + 1], indices[i], indices[i + 2]);
    } else {
      for (size_t i = 1; i + 1 < indices.size(); ++i) emit(indices[0], indices[i], indices[i + 1]);
    }
  }

  const tinygltf::Model& model_;
  const GltfSource& source_;
  std::vector<bool> visited_;
  Mesh mesh_;
  bool haveNormals_ = true;
};

}  // namespace

Mesh loadGltf(const std::string& path, std::vector<std::string>* warnings) {
  const bool binary = std::filesystem::path(path).extension() == ".glb";
  const GltfSource source(path, binary);
  Json root = parseJson(source);
  Schema(source).check(root);
  checkBuffers(root, source);
  std::string json = geometryOnly(root);

  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks(tinygltf::FsCallbacks{&fileExists, &expandFilePath, &readWholeFile, &writeWholeFile, nullptr});
  loader.SetImageLoader(&skipImage, nullptr);
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  const std::string baseDir = parent.empty() ? std::string(".") : parent.string();
  std::string err, warn;
  bool ok = false;
  if (binary) {
    const std::string glb = rebuildGlb(std::move(json), source.bin(), !source.bin().empty());
    ok = loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(glb.data()),
                                     static_cast<unsigned int>(glb.size()), baseDir);
  } else {
    ok = loader.LoadASCIIFromString(&model, &err, &warn, json.data(), static_cast<unsigned int>(json.size()), baseDir);
  }
  if (!ok) {
    // Whatever the checks above did not foresee: no position is known, so none is claimed.
    while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
    throw SceneError(SourceLocation{path, 0, 0}, "cannot read glTF: " + (err.empty() ? "unknown error" : err));
  }
  if (warnings && !warn.empty()) warnings->push_back(path + ": " + warn);
  GltfReader reader(model, source);
  Mesh mesh = reader.read();
  return finishImportedMesh(std::move(mesh), reader.haveNormals(), path, warnings);
}

}  // namespace shadowref
