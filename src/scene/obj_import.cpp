// Wavefront OBJ: one pass that both checks and reads the file, so that what is accepted and what is
// imported cannot disagree (a second parser once accepted the hexadecimal float 0x1p3 as 8 while
// the importer read it as 0). Only `v`, `vt`, `vn` and `f` are read; `mtllib` is not opened
// because the renderer takes materials from the scene file.
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string_view>
#include <unordered_map>

#include "scene/input_file.h"
#include "scene/mesh_import.h"
#include "scene/scene_error.h"

namespace shadowref {

namespace {

constexpr uint32_t kNoNormal = std::numeric_limits<uint32_t>::max();
const char* const kKindNames[3] = {"vertex", "texture coordinate", "normal"};

class ObjParser {
 public:
  explicit ObjParser(const std::string& path) : path_(path) {}

  Mesh read(std::vector<std::string>* warnings) {
    const std::string bytes = readInputFile(path_, "mesh file");
    std::string_view rest(bytes);
    while (!rest.empty()) {
      const size_t end = rest.find('\n');
      std::string_view text = rest.substr(0, end);
      rest = end == std::string_view::npos ? std::string_view() : rest.substr(end + 1);
      ++line_;
      if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
      parseLine(text);
    }
    // Positive indices may name vertices defined further down: checked against the totals.
    for (const ForwardUse& use : forward_)
      if (use.value > count_[use.kind])
        fail(use.line, use.column,
             std::string(kKindNames[use.kind]) + " index " + std::to_string(use.value) +
                 " out of range (the file has " + std::to_string(count_[use.kind]) + ")");
    return build(warnings);
  }

 private:
  struct Token {
    std::string_view text;
    int column;  // 1-based
  };
  struct ForwardUse {
    int line, column;
    uint64_t value;
    int kind;
  };
  struct Face {
    size_t first, count;  // into corners_
    int line, column;
  };
  struct Corner {
    uint32_t vertex, normal;
  };

  [[noreturn]] void fail(int line, int column, const std::string& message) const {
    throw SceneError(SourceLocation{path_, line, column}, message);
  }

  void parseLine(std::string_view text) {
    std::vector<Token>& tokens = tokens_;
    tokens.clear();
    for (size_t p = 0; p < text.size();) {
      p = text.find_first_not_of(" \t", p);
      if (p == std::string_view::npos) break;
      const size_t q = text.find_first_of(" \t", p);
      tokens.push_back({text.substr(p, q == std::string_view::npos ? std::string_view::npos : q - p),
                        static_cast<int>(std::min<size_t>(p + 1, std::numeric_limits<int>::max()))});
      p = q;
    }
    if (tokens.empty() || tokens[0].text[0] == '#') return;
    const std::string_view keyword = tokens[0].text;
    const int kind = keyword == "v" ? 0 : keyword == "vt" ? 1 : keyword == "vn" ? 2 : -1;
    if (kind >= 0) {
      const size_t needed = kind == 1 ? 1 : 3;
      if (tokens.size() - 1 < needed)
        fail(line_, static_cast<int>(std::min<size_t>(text.size() + 1, std::numeric_limits<int>::max())),
             std::string(kKindNames[kind]) + " needs " + std::to_string(needed) + " coordinates");
      double xyz[3] = {0, 0, 0};
      for (size_t i = 1; i < tokens.size(); ++i) {
        const double value = number(tokens[i]);
        if (i <= 3) xyz[i - 1] = value;
      }
      ++count_[kind];
      if (kind == 0) positions_.emplace_back(xyz[0], xyz[1], xyz[2]);
      if (kind == 2) normals_.emplace_back(xyz[0], xyz[1], xyz[2]);
    } else if (keyword == "f") {
      if (tokens.size() < 4) fail(line_, tokens[0].column, "face needs at least three vertices");
      faces_.push_back({corners_.size(), tokens.size() - 1, line_, tokens[0].column});
      for (size_t i = 1; i < tokens.size(); ++i) corners_.push_back(corner(tokens[i]));
    }
    // Anything else (o, g, s, usemtl, mtllib, l, p, ...) carries nothing the renderer uses.
  }

  // A coordinate: a finite decimal number, as the OBJ format writes them.
  double number(const Token& token) const {
    std::string_view s = token.text;
    if (s.size() > 1 && s[0] == '+' && s[1] != '-' && s[1] != '+') s.remove_prefix(1);  // from_chars takes no '+'
    double value = 0.0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value, std::chars_format::general);
    const std::string quoted = "'" + std::string(token.text) + "'";
    if (s.find_first_of("xX") != std::string_view::npos)
      fail(line_, token.column, quoted + " is a hexadecimal number; OBJ coordinates are decimal");
    if (ec == std::errc::result_out_of_range) fail(line_, token.column, quoted + " is out of the range of a double");
    if (ec != std::errc() || end != s.data() + s.size()) fail(line_, token.column, quoted + " is not a number");
    if (!std::isfinite(value)) fail(line_, token.column, "coordinate is NaN or infinite");
    return value;
  }

  // One face corner: v, v/vt, v//vn or v/vt/vn, each index 1-based or negative (counted back from
  // the last one so far). Resolved to 0-based indices without any arithmetic that can overflow.
  Corner corner(const Token& token) {
    Corner c{0, kNoNormal};
    size_t start = 0;
    for (int part = 0; part < 3 && start <= token.text.size(); ++part) {
      const size_t slash = token.text.find('/', start);
      const std::string_view field =
          token.text.substr(start, slash == std::string_view::npos ? std::string_view::npos : slash - start);
      const int column = token.column + static_cast<int>(std::min<size_t>(start, 1u << 20));
      if (!field.empty() || part == 0) {
        const uint32_t index = resolve(field, part, token, column);
        if (part == 0) c.vertex = index;
        if (part == 2) c.normal = index;
      }
      if (slash == std::string_view::npos) break;
      start = slash + 1;
    }
    return c;
  }

  uint32_t resolve(std::string_view field, int kind, const Token& token, int column) {
    int64_t value = 0;
    const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), value);
    const std::string name = kKindNames[kind];
    if (ec == std::errc::result_out_of_range)
      fail(line_, column, name + " index '" + std::string(field) + "' out of range");
    if (field.empty() || ec != std::errc() || end != field.data() + field.size())
      fail(line_, column, "'" + std::string(token.text) + "' is not a face index");
    if (value == 0) fail(line_, column, name + " index 0 (OBJ counts from 1)");
    const uint64_t count = count_[kind];
    if (value < 0) {
      // count < 2^32 and value >= INT64_MIN: the sum cannot overflow, and no negation is needed.
      const int64_t resolved = static_cast<int64_t>(count) + value;
      if (resolved < 0)
        fail(line_, column,
             name + " index " + std::to_string(value) + " reaches before the first " + name + " (" +
                 std::to_string(count) + " so far)");
      return static_cast<uint32_t>(resolved);
    }
    const auto positive = static_cast<uint64_t>(value);
    // More vertices than a uint32_t can count cannot fit in kMaxInputFileBytes.
    if (positive > std::numeric_limits<uint32_t>::max())
      fail(line_, column, name + " index " + std::to_string(value) + " out of range");
    if (positive > count) forward_.push_back({line_, column, positive, kind});
    return static_cast<uint32_t>(positive - 1);
  }

  Mesh build(std::vector<std::string>* warnings) {
    Mesh mesh;
    mesh.name = std::filesystem::path(path_).stem().string();
    bool haveNormals = true;
    // One render vertex per (position, normal) index pair, in order of first use.
    std::unordered_map<uint64_t, uint32_t> vertexOf;
    vertexOf.reserve(corners_.size());
    auto vertex = [&](const Corner& c) {
      if (c.normal == kNoNormal) haveNormals = false;
      auto [it, inserted] = vertexOf.try_emplace((uint64_t{c.vertex} << 32) | c.normal,
                                                 static_cast<uint32_t>(mesh.positions.size()));
      if (inserted) {
        mesh.positions.push_back(positions_[c.vertex]);
        mesh.normals.push_back(c.normal == kNoNormal ? glm::dvec3(0.0) : normals_[c.normal]);
      }
      return it->second;
    };
    std::vector<glm::uvec3> local;
    for (const Face& face : faces_) {
      local.clear();
      triangulate(face, local, warnings);
      for (const glm::uvec3& t : local) {
        glm::uvec3 out;
        for (int i = 0; i < 3; ++i) out[i] = vertex(corners_[face.first + t[i]]);
        mesh.triangles.push_back(out);
      }
    }
    return finishImportedMesh(std::move(mesh), haveNormals, path_, warnings);
  }

  glm::dvec3 at(const Face& face, size_t i) const { return positions_[corners_[face.first + i].vertex]; }

  // Triangles of one face as corner numbers within the face, in O(n) for convex faces.
  void triangulate(const Face& face, std::vector<glm::uvec3>& out, std::vector<std::string>* warnings) const {
    const size_t n = face.count;
    if (n == 3) {
      out.emplace_back(0, 1, 2);
      return;
    }
    // Newell's normal: the face's orientation, robust for non-planar faces.
    glm::dvec3 normal(0.0);
    for (size_t i = 0; i < n; ++i) {
      const glm::dvec3 a = at(face, i), b = at(face, (i + 1) % n);
      normal += glm::dvec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
    }
    if (isConvex(face, normal)) {
      if (n == 4) {
        // Split along the shorter diagonal (as tinyobjloader did, so quads triangulate as before).
        const glm::dvec3 d02 = at(face, 2) - at(face, 0), d13 = at(face, 3) - at(face, 1);
        if (glm::dot(d02, d02) < glm::dot(d13, d13)) {
          out.emplace_back(0, 1, 2);
          out.emplace_back(0, 2, 3);
        } else {
          out.emplace_back(0, 1, 3);
          out.emplace_back(1, 2, 3);
        }
        return;
      }
      for (uint32_t i = 1; i + 1 < n; ++i) out.emplace_back(0, i, i + 1);
      return;
    }
    if (n > kMaxNonConvexCorners)
      fail(face.line, face.column,
           "face with " + std::to_string(n) + " corners is not convex; non-convex faces may have at most " +
               std::to_string(kMaxNonConvexCorners) + " corners (split it)");
    earClip(face, normal, out, warnings);
  }

  // Convex for a fan: every corner turns the same way as the face's normal, and every fan triangle
  // from corner 0 faces that way too (which rules out stars that wind around twice).
  bool isConvex(const Face& face, const glm::dvec3& normal) const {
    const size_t n = face.count;
    const glm::dvec3 origin = at(face, 0);
    for (size_t i = 0; i < n; ++i) {
      const glm::dvec3 a = at(face, i), b = at(face, (i + 1) % n), c = at(face, (i + 2) % n);
      if (glm::dot(glm::cross(b - a, c - b), normal) < 0.0) return false;
      if (i >= 1 && i + 1 < n && glm::dot(glm::cross(a - origin, b - origin), normal) < 0.0) return false;
    }
    return true;
  }

  // Ear clipping in the plane that drops the normal's largest axis: O(n^3) at worst, hence the
  // corner limit. A face that has no ear left (self-intersecting) keeps the rest as a fan.
  void earClip(const Face& face, const glm::dvec3& normal, std::vector<glm::uvec3>& out,
               std::vector<std::string>* warnings) const {
    const size_t n = face.count;
    const glm::dvec3 m = glm::abs(normal);
    const int drop = m.x >= m.y && m.x >= m.z ? 0 : m.y >= m.z ? 1 : 2;
    const int u = (drop + 1) % 3, v = (drop + 2) % 3;
    const double sign = normal[drop] < 0.0 ? -1.0 : 1.0;  // counter-clockwise in (u, v) after this
    std::vector<glm::dvec2> p(n);
    for (size_t i = 0; i < n; ++i) p[i] = {at(face, i)[u], sign * at(face, i)[v]};
    auto cross = [&](size_t a, size_t b, size_t c) {
      return (p[b].x - p[a].x) * (p[c].y - p[a].y) - (p[b].y - p[a].y) * (p[c].x - p[a].x);
    };
    std::vector<uint32_t> ring(n);
    for (uint32_t i = 0; i < n; ++i) ring[i] = i;
    while (ring.size() > 3) {
      bool clipped = false;
      for (size_t k = 0; k < ring.size() && !clipped; ++k) {
        const uint32_t a = ring[(k + ring.size() - 1) % ring.size()], b = ring[k], c = ring[(k + 1) % ring.size()];
        if (!(cross(a, b, c) > 0.0)) continue;  // reflex or straight corner
        bool inside = false;
        for (uint32_t q : ring) {
          if (q == a || q == b || q == c) continue;
          if (cross(a, b, q) >= 0.0 && cross(b, c, q) >= 0.0 && cross(c, a, q) >= 0.0) {
            inside = true;
            break;
          }
        }
        if (inside) continue;
        out.emplace_back(a, b, c);
        ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(k));
        clipped = true;
      }
      if (!clipped) {
        if (warnings)
          warnings->push_back(path_ + ":" + std::to_string(face.line) +
                              ": face intersects itself; the rest is triangulated as a fan");
        for (size_t i = 1; i + 1 < ring.size(); ++i) out.emplace_back(ring[0], ring[i], ring[i + 1]);
        return;
      }
    }
    out.emplace_back(ring[0], ring[1], ring[2]);
  }

  const std::string& path_;
  int line_ = 0;
  uint64_t count_[3] = {0, 0, 0};
  std::vector<glm::dvec3> positions_, normals_;
  std::vector<Corner> corners_;
  std::vector<Face> faces_;
  std::vector<ForwardUse> forward_;
  std::vector<Token> tokens_;
};

}  // namespace

Mesh loadObj(const std::string& path, std::vector<std::string>* warnings) {
  return ObjParser(path).read(warnings);
}

}  // namespace shadowref
