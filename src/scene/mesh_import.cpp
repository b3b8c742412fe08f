#include "scene/mesh_import.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include <tiny_obj_loader.h>

// tinygltf: this is the one translation unit that compiles its implementation. Images are not
// needed for geometry, so none of the image code is built or run.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include "scene/adjacency.h"
#include "scene/scene_error.h"

namespace shadowref {

namespace {

[[noreturn]] void fail(const std::string& path, int line, int column, const std::string& message) {
  throw SceneError(SourceLocation{path, line, column}, message);
}

void requireReadableFile(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) fail(path, 0, 0, "mesh file not found");
  if (!std::filesystem::is_regular_file(path, ec)) fail(path, 0, 0, "mesh file is not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, 0, 0, "cannot open mesh file");
}

// Normals, welding and adjacency for a freshly read mesh; rejects what has nothing to draw.
Mesh finishImport(Mesh mesh, bool haveNormals, const std::string& path,
                  std::vector<std::string>* warnings) {
  if (mesh.triangles.empty()) fail(path, 0, 0, "mesh has no triangles");
  for (const glm::dvec3& p : mesh.positions)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      fail(path, 0, 0, "vertex coordinate is NaN or infinite");
  if (haveNormals)
    for (glm::dvec3& n : mesh.normals) {
      const double length = glm::length(n);
      if (!(length > 0.0) || !std::isfinite(length)) {
        haveNormals = false;
        break;
      }
      n /= length;
    }
  if (!haveNormals) computeCreaseNormals(mesh);
  buildAdjacency(mesh, warnings);
  if (mesh.triangles.empty()) fail(path, 0, 0, "mesh has no triangles that are not degenerate");
  return mesh;
}

// ---------------------------------------------------------------------------------------------
// OBJ

// Reads the OBJ once for what tinyobjloader does not check: every face index must name an existing
// vertex (1-based, or negative relative to the vertices so far; 0 is never valid), coordinates must
// be finite numbers. Reports line and column of the offending token.
void validateObj(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  struct IndexUse {
    int line, column;
    long value;
    int kind;  // 0 v, 1 vt, 2 vn
  };
  std::vector<IndexUse> positive;
  long count[3] = {0, 0, 0};
  static const char* kNames[3] = {"vertex", "texture coordinate", "normal"};
  std::string text;
  int line = 0;
  while (std::getline(in, text)) {
    ++line;
    if (!text.empty() && text.back() == '\r') text.pop_back();
    size_t pos = text.find_first_not_of(" \t");
    if (pos == std::string::npos || text[pos] == '#') continue;
    size_t end = text.find_first_of(" \t", pos);
    const std::string keyword = text.substr(pos, end == std::string::npos ? std::string::npos : end - pos);
    // Tokens after the keyword, with their 1-based columns.
    std::vector<std::pair<std::string, int>> tokens;
    for (size_t p = end; p != std::string::npos && p < text.size();) {
      p = text.find_first_not_of(" \t", p);
      if (p == std::string::npos) break;
      size_t q = text.find_first_of(" \t", p);
      tokens.emplace_back(text.substr(p, q == std::string::npos ? std::string::npos : q - p),
                          static_cast<int>(p) + 1);
      p = q;
    }
    const int kind = keyword == "v" ? 0 : keyword == "vt" ? 1 : keyword == "vn" ? 2 : -1;
    if (kind >= 0) {
      const size_t needed = kind == 1 ? 1 : 3;
      if (tokens.size() < needed)
        fail(path, line, static_cast<int>(text.size()) + 1,
             std::string(kNames[kind]) + " needs " + std::to_string(needed) + " coordinates");
      for (const auto& [token, column] : tokens) {
        char* stop = nullptr;
        const double value = std::strtod(token.c_str(), &stop);
        if (stop == token.c_str() || *stop != '\0')
          fail(path, line, column, "'" + token + "' is not a number");
        if (!std::isfinite(value)) fail(path, line, column, "coordinate is NaN or infinite");
      }
      ++count[kind];
    } else if (keyword == "f") {
      if (tokens.size() < 3) fail(path, line, pos + 1, "face needs at least three vertices");
      for (const auto& [token, column] : tokens) {
        // v, v/vt, v//vn, v/vt/vn
        size_t start = 0;
        for (int part = 0; part < 3 && start <= token.size(); ++part) {
          size_t slash = token.find('/', start);
          const std::string field = token.substr(start, slash == std::string::npos ? std::string::npos : slash - start);
          const int fieldColumn = column + static_cast<int>(start);
          if (!field.empty() || part == 0) {
            char* stop = nullptr;
            const long value = std::strtol(field.c_str(), &stop, 10);
            if (field.empty() || *stop != '\0') fail(path, line, fieldColumn, "'" + token + "' is not a face index");
            if (value == 0) fail(path, line, fieldColumn, std::string(kNames[part]) + " index 0 (OBJ counts from 1)");
            if (value < 0 && -value > count[part])
              fail(path, line, fieldColumn,
                   std::string(kNames[part]) + " index " + std::to_string(value) + " reaches before the first " +
                       kNames[part] + " (" + std::to_string(count[part]) + " so far)");
            if (value > 0) positive.push_back({line, fieldColumn, value, part});
          }
          if (slash == std::string::npos) break;
          start = slash + 1;
        }
      }
    }
  }
  if (in.bad()) fail(path, line, 0, "read error");
  // Positive indices may refer to vertices defined further down: check against the totals.
  for (const IndexUse& use : positive)
    if (use.value > count[use.kind])
      fail(path, use.line, use.column,
           std::string(kNames[use.kind]) + " index " + std::to_string(use.value) + " out of range (the file has " +
               std::to_string(count[use.kind]) + ")");
}

}  // namespace

Mesh loadObj(const std::string& path, std::vector<std::string>* warnings) {
  requireReadableFile(path);
  validateObj(path);

  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path, config)) fail(path, 0, 0, "cannot read OBJ: " + reader.Error());
  if (warnings && !reader.Warning().empty()) warnings->push_back(path + ": " + reader.Warning());

  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  Mesh mesh;
  mesh.name = std::filesystem::path(path).stem().string();
  bool haveNormals = true;
  // One render vertex per (position, normal) index pair, in order of first use.
  std::map<std::pair<int, int>, uint32_t> vertexOf;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const auto& indices = shape.mesh.indices;
    size_t offset = 0;
    for (unsigned char corners : shape.mesh.num_face_vertices) {
      if (corners != 3 || offset + 3 > indices.size()) fail(path, 0, 0, "face could not be triangulated");
      glm::uvec3 triangle;
      for (int i = 0; i < 3; ++i) {
        const tinyobj::index_t idx = indices[offset + i];
        if (idx.vertex_index < 0 || 3 * size_t(idx.vertex_index) + 2 >= attrib.vertices.size())
          fail(path, 0, 0, "vertex index out of range");
        int normal = idx.normal_index;
        if (normal >= 0 && 3 * size_t(normal) + 2 >= attrib.normals.size()) normal = -1;
        if (normal < 0) haveNormals = false;
        auto [it, inserted] = vertexOf.try_emplace({idx.vertex_index, normal},
                                                   static_cast<uint32_t>(mesh.positions.size()));
        if (inserted) {
          const float* v = &attrib.vertices[3 * size_t(idx.vertex_index)];
          mesh.positions.emplace_back(v[0], v[1], v[2]);
          if (normal >= 0) {
            const float* n = &attrib.normals[3 * size_t(normal)];
            mesh.normals.emplace_back(n[0], n[1], n[2]);
          } else {
            mesh.normals.emplace_back(0.0);
          }
        }
        triangle[i] = it->second;
      }
      mesh.triangles.push_back(triangle);
      offset += 3;
    }
  }
  return finishImport(std::move(mesh), haveNormals, path, warnings);
}

// ---------------------------------------------------------------------------------------------
// glTF 2.0

namespace {

// Ignores images: only geometry is read.
bool skipImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int,
               void*) {
  return true;
}

// nlohmann's parse errors say "at line L, column C": keep that position.
SourceLocation locateGltfError(const std::string& path, const std::string& err) {
  SourceLocation at{path, 0, 0};
  std::smatch m;
  static const std::regex kAt("line ([0-9]+), column ([0-9]+)");
  if (std::regex_search(err, m, kAt)) {
    at.line = std::stoi(m[1].str());
    at.column = std::stoi(m[2].str());
  }
  return at;
}

class GltfReader {
 public:
  GltfReader(const tinygltf::Model& model, const std::string& path) : model_(model), path_(path) {}

  Mesh read() {
    std::vector<int> roots;
    if (!model_.scenes.empty()) {
      const int s = model_.defaultScene >= 0 ? model_.defaultScene : 0;
      if (s >= static_cast<int>(model_.scenes.size())) fail(path_, 0, 0, "default scene index out of range");
      roots = model_.scenes[s].nodes;
    } else {
      std::vector<bool> isChild(model_.nodes.size(), false);
      for (const tinygltf::Node& n : model_.nodes)
        for (int c : n.children)
          if (c >= 0 && c < static_cast<int>(isChild.size())) isChild[c] = true;
      for (size_t i = 0; i < model_.nodes.size(); ++i)
        if (!isChild[i]) roots.push_back(static_cast<int>(i));
    }
    for (int n : roots) visit(n, glm::dmat4(1.0), 0);
    mesh_.name = std::filesystem::path(path_).stem().string();
    return std::move(mesh_);
  }

  bool haveNormals() const { return haveNormals_; }

 private:
  static constexpr int kMaxDepth = 256;

  void visit(int index, const glm::dmat4& parent, int depth) {
    if (index < 0 || index >= static_cast<int>(model_.nodes.size())) fail(path_, 0, 0, "node index out of range");
    if (depth > kMaxDepth) fail(path_, 0, 0, "node hierarchy too deep (a cycle?)");
    const tinygltf::Node& node = model_.nodes[index];
    const glm::dmat4 world = parent * localMatrix(node);
    if (node.mesh >= 0) {
      if (node.mesh >= static_cast<int>(model_.meshes.size())) fail(path_, 0, 0, "mesh index out of range");
      for (const tinygltf::Primitive& p : model_.meshes[node.mesh].primitives) addPrimitive(p, world);
    }
    for (int child : node.children) visit(child, world, depth + 1);
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

  // The bytes of element i of an accessor, after checking that all `count` elements lie inside
  // the buffer view and the buffer.
  struct View {
    const unsigned char* data = nullptr;
    size_t stride = 0, count = 0;
    const unsigned char* at(size_t i) const { return data + i * stride; }
  };

  View view(int accessorIndex, int type, std::initializer_list<int> componentTypes, const char* what) const {
    if (accessorIndex < 0 || accessorIndex >= static_cast<int>(model_.accessors.size()))
      fail(path_, 0, 0, std::string(what) + ": accessor index out of range");
    const tinygltf::Accessor& a = model_.accessors[accessorIndex];
    if (a.sparse.isSparse) fail(path_, 0, 0, std::string(what) + ": sparse accessors are not supported");
    if (a.type != type) fail(path_, 0, 0, std::string(what) + ": accessor has the wrong type");
    bool typeOk = false;
    for (int c : componentTypes) typeOk |= a.componentType == c;
    if (!typeOk) fail(path_, 0, 0, std::string(what) + ": unsupported component type");
    if (a.bufferView < 0 || a.bufferView >= static_cast<int>(model_.bufferViews.size()))
      fail(path_, 0, 0, std::string(what) + ": accessor has no valid buffer view");
    const tinygltf::BufferView& bv = model_.bufferViews[a.bufferView];
    if (bv.buffer < 0 || bv.buffer >= static_cast<int>(model_.buffers.size()))
      fail(path_, 0, 0, std::string(what) + ": buffer index out of range");
    const std::vector<unsigned char>& buffer = model_.buffers[bv.buffer].data;
    const int stride = a.ByteStride(bv);
    const int elementSize = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(a.componentType)) *
                            tinygltf::GetNumComponentsInType(static_cast<uint32_t>(a.type));
    if (stride <= 0 || elementSize <= 0) fail(path_, 0, 0, std::string(what) + ": invalid byte stride");
    View v;
    v.stride = static_cast<size_t>(stride);
    v.count = a.count;
    if (a.count > 0) {
      const size_t last = a.byteOffset + (a.count - 1) * v.stride + static_cast<size_t>(elementSize);
      if (bv.byteOffset > buffer.size() || bv.byteLength > buffer.size() - bv.byteOffset ||
          a.count > (SIZE_MAX / 2) / v.stride || last > bv.byteLength)
        fail(path_, 0, 0, std::string(what) + ": accessor reaches outside its buffer");
      v.data = buffer.data() + bv.byteOffset + a.byteOffset;
    }
    return v;
  }

  std::vector<glm::dvec3> readVec3(int accessor, const char* what) const {
    const View v = view(accessor, TINYGLTF_TYPE_VEC3, {TINYGLTF_COMPONENT_TYPE_FLOAT}, what);
    std::vector<glm::dvec3> out(v.count);
    for (size_t i = 0; i < v.count; ++i) {
      float f[3];
      std::memcpy(f, v.at(i), sizeof f);
      out[i] = {f[0], f[1], f[2]};
    }
    return out;
  }

  std::vector<uint32_t> readIndices(int accessor) const {
    const View v = view(accessor, TINYGLTF_TYPE_SCALAR,
                        {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                         TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT},
                        "indices");
    const int type = model_.accessors[accessor].componentType;
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
    }
    return out;
  }

  void addPrimitive(const tinygltf::Primitive& p, const glm::dmat4& world) {
    const int mode = p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        mode != TINYGLTF_MODE_TRIANGLE_FAN)
      return;  // points and lines have no surface
    auto position = p.attributes.find("POSITION");
    if (position == p.attributes.end()) fail(path_, 0, 0, "primitive without POSITION");
    const std::vector<glm::dvec3> positions = readVec3(position->second, "POSITION");
    std::vector<glm::dvec3> normals;
    if (auto normal = p.attributes.find("NORMAL"); normal != p.attributes.end()) {
      normals = readVec3(normal->second, "NORMAL");
      if (normals.size() != positions.size()) fail(path_, 0, 0, "NORMAL and POSITION counts differ");
    } else {
      haveNormals_ = false;
    }
    std::vector<uint32_t> indices;
    if (p.indices >= 0) {
      indices = readIndices(p.indices);
      for (uint32_t i : indices)
        if (i >= positions.size()) fail(path_, 0, 0, "index " + std::to_string(i) + " out of range");
    } else {
      indices.resize(positions.size());
      for (uint32_t i = 0; i < indices.size(); ++i) indices[i] = i;
    }
    // A mirroring transform turns the winding around; normals go through the inverse transpose.
    const glm::dmat3 linear(world);
    const bool mirrored = glm::determinant(linear) < 0.0;
    const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(linear));
    const uint32_t base = static_cast<uint32_t>(mesh_.positions.size());
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
  const std::string& path_;
  Mesh mesh_;
  bool haveNormals_ = true;
};

}  // namespace

Mesh loadGltf(const std::string& path, std::vector<std::string>* warnings) {
  requireReadableFile(path);
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&skipImage, nullptr);
  std::string err, warn;
  const bool binary = std::filesystem::path(path).extension() == ".glb";
  const bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                         : loader.LoadASCIIFromFile(&model, &err, &warn, path);
  if (!ok) {
    while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
    throw SceneError(locateGltfError(path, err), "cannot read glTF: " + (err.empty() ? "unknown error" : err));
  }
  if (warnings && !warn.empty()) warnings->push_back(path + ": " + warn);
  GltfReader reader(model, path);
  Mesh mesh = reader.read();
  return finishImport(std::move(mesh), reader.haveNormals(), path, warnings);
}

}  // namespace shadowref
