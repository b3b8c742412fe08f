#include "scene/scene_nodes.h"

#include "scene/resource_limits.h"

#include <optional>
#include <string_view>
#include <unordered_map>

#include <glm/gtc/matrix_transform.hpp>

namespace shadowref {

namespace {

constexpr double kPi = 3.14159265358979323846;

double radians(double degrees) { return degrees * (kPi / 180.0); }

// Mesh and material names -> indices; the first of equal names wins, as a linear search would.
// `instances` counts the mesh nodes against the budget as they are read: a file whose aliases
// repeat a large mesh is rejected at the first node too many, before the rest are read (the
// budget is checked again, authoritatively, with the world transforms in validateScene).
struct NameIndex {
  std::unordered_map<std::string_view, int> meshes, materials;
  ResourceBudget* instances = nullptr;
  explicit NameIndex(const Scene& scene) {
    for (size_t i = 0; i < scene.meshes.size(); ++i) meshes.emplace(scene.meshes[i]->name, static_cast<int>(i));
    for (size_t i = 0; i < scene.materials.size(); ++i) materials.emplace(scene.materials[i].name, static_cast<int>(i));
  }
};

// A node as written, before its transform is composed (the keys may come in any order).
struct NodeDraft {
  const Scene* scene = nullptr;
  const NameIndex* index = nullptr;
  std::string path;
  const YamlValue* children = nullptr;
  Node node;
  std::optional<glm::dvec3> translate, scale;
  std::optional<glm::dmat4> rotate, matrix;
  SourceLocation scaleAt, matrixAt;
  bool nameGiven = false;
};

// The index of the name `v` holds; an unknown name is an error that suggests the closest of
// `names` (built only then).
template <class NamesFn>
int findByName(const std::unordered_map<std::string_view, int>& index, NamesFn allNames, const YamlValue& v,
               const std::string& path, const char* what) {
  std::string name = readText(v, path);
  if (auto it = index.find(name); it != index.end()) return it->second;
  const std::vector<std::string_view> names = allNames();
  std::string message = path + ": no " + std::string(what) + " named '" + name + "'";
  std::string_view near = closestName(name, names);
  if (!near.empty()) message += "; did you mean '" + std::string(near) + "'?";
  else if (names.empty()) message += " (the scene defines none)";
  failAt(v.at, message);
}

int findMesh(const NodeDraft& d, const YamlValue& v, const std::string& path) {
  return findByName(d.index->meshes, [&] {
    std::vector<std::string_view> names;
    for (const auto& m : d.scene->meshes) names.push_back(m->name);
    return names;
  }, v, path, "mesh");
}

int findMaterial(const NodeDraft& d, const YamlValue& v, const std::string& path) {
  return findByName(d.index->materials, [&] {
    std::vector<std::string_view> names;
    for (const Material& m : d.scene->materials) names.push_back(m.name);
    return names;
  }, v, path, "material");
}

Node readNode(const YamlValue& map, const std::string& path, const Scene& scene, const NameIndex& index,
              Provenance& where);

// rotate: {axis: [x, y, z], angle: degrees} or {euler: [x, y, z]} in degrees, applied about the
// fixed X axis first, then Y, then Z: R = Rz · Ry · Rx.
struct RotateDraft {
  std::optional<glm::dvec3> axis, euler;
  std::optional<double> angle;
};

glm::dmat4 readRotate(const YamlValue& v, const std::string& path) {
  static const std::vector<Field<RotateDraft>> fields{
      {"axis", [](const YamlValue& x, RotateDraft& r, const std::string& p, Provenance&) {
         r.axis = readDirection(x, p, "the rotation axis");
       }},
      {"angle", [](const YamlValue& x, RotateDraft& r, const std::string& p, Provenance&) { r.angle = readNumber(x, p); }},
      {"euler", [](const YamlValue& x, RotateDraft& r, const std::string& p, Provenance&) { r.euler = readVec3(x, p); }},
  };
  if (!v.isMap()) failAt(v.at, path + ": expected {axis: [x, y, z], angle: degrees} or {euler: [x, y, z]}");
  RotateDraft r;
  Provenance ignored{v.at};
  applyFields(v, path, fields, r, ignored);
  if (r.euler && (r.axis || r.angle))
    failAt(v.at, path + ": give either euler or axis and angle, not both");
  if (r.euler) {
    const glm::dvec3 e = *r.euler;
    const glm::dmat4 id(1.0);
    return glm::rotate(id, radians(e.z), glm::dvec3(0, 0, 1)) * glm::rotate(id, radians(e.y), glm::dvec3(0, 1, 0)) *
           glm::rotate(id, radians(e.x), glm::dvec3(1, 0, 0));
  }
  if (!r.axis || !r.angle) failAt(v.at, path + ": a rotation about an axis needs both axis and angle");
  return glm::rotate(glm::dmat4(1.0), radians(*r.angle), glm::normalize(*r.axis));
}

glm::dvec3 readScale(const YamlValue& v, const std::string& path) {
  glm::dvec3 s = v.isScalar() ? glm::dvec3(readNumber(v, path)) : readVec3(v, path);
  if (s.x == 0.0 || s.y == 0.0 || s.z == 0.0)
    failAt(v.at, path + ": a scale of 0 flattens the node: the transform is singular");
  return s;
}

// matrix: 16 numbers written row by row, as on paper (the translation is the 4th, 8th and 12th
// number), either flat or as 4 rows of 4. The last row must be 0 0 0 1: nodes are affine.
glm::dmat4 readMatrix(const YamlValue& v, const std::string& path) {
  std::vector<const YamlValue*> numbers;
  if (v.isList() && v.items.size() == 4 && v.items[0].isList()) {
    for (const YamlValue& row : v.items) {
      if (!row.isList() || row.items.size() != 4) failAt(row.at, path + ": each of the 4 rows needs 4 numbers");
      for (const YamlValue& x : row.items) numbers.push_back(&x);
    }
  } else if (v.isList() && v.items.size() == 16) {
    for (const YamlValue& x : v.items) numbers.push_back(&x);
  } else {
    failAt(v.at, path + ": expected 16 numbers, row by row (flat or as 4 rows of 4)");
  }
  glm::dmat4 m(0.0);
  for (int i = 0; i < 16; ++i) m[i % 4][i / 4] = readNumber(*numbers[i], path + "." + std::to_string(i));  // glm: m[column][row]
  if (m[0][3] != 0.0 || m[1][3] != 0.0 || m[2][3] != 0.0 || m[3][3] != 1.0)
    failAt(v.at, path + ": the last row must be 0 0 0 1 (an affine transform)");
  // Singular when the determinant is negligible against the largest it could be for these column
  // lengths (Hadamard's bound), so the test does not depend on the scene's units.
  const glm::dmat3 linear(m);
  const double bound = glm::length(linear[0]) * glm::length(linear[1]) * glm::length(linear[2]);
  if (!(std::abs(glm::determinant(linear)) > 1e-12 * bound))
    failAt(v.at, path + ": the matrix is singular (its upper 3x3 part has determinant 0)");
  return m;
}

const std::vector<Field<NodeDraft>>& nodeFields() {
  static const std::vector<Field<NodeDraft>> fields{
      {"name", [](const YamlValue& v, NodeDraft& d, const std::string& p, Provenance&) {
         d.node.name = readText(v, p);
         if (d.node.name.find_first_of("/.") != std::string::npos)
           failAt(v.at, p + ": a node name must not contain '/' or '.' (they separate names in paths)");
         d.nameGiven = true;
       }},
      {"mesh", [](const YamlValue& v, NodeDraft& d, const std::string& p, Provenance&) {
         d.node.mesh = findMesh(d, v, p);
       }},
      {"material", [](const YamlValue& v, NodeDraft& d, const std::string& p, Provenance&) {
         d.node.material = findMaterial(d, v, p);
       }},
      {"translate", [](const YamlValue& v, NodeDraft& d, const std::string& p, Provenance&) { d.translate = readVec3(v, p); }},
      {"rotate", [](const YamlValue& v, NodeDraft& d, const std::string& p, Provenance&) { d.rotate = readRotate(v, p); }},
      {"scale", [](const YamlValue& v, NodeDraft& d, const std::string& p, Provenance&) {
         d.scale = readScale(v, p);
         d.scaleAt = v.at;
       }},
      {"matrix", [](const YamlValue& v, NodeDraft& d, const std::string& p, Provenance&) {
         d.matrix = readMatrix(v, p);
         d.matrixAt = v.at;
       }},
      {"cast_shadows", [](const YamlValue& v, NodeDraft& d, const std::string& p, Provenance&) {
         d.node.castShadows = readBool(v, p);
       }},
      {"shadow_proxy", [](const YamlValue& v, NodeDraft& d, const std::string& p, Provenance&) {
         d.node.shadowProxy = findMesh(d, v, p);
       }},
      {"children", [](const YamlValue& v, NodeDraft& d, const std::string&, Provenance&) {
         // Read after the node's own keys (readNode): a node is counted before its children.
         if (v.isNull()) return;
         if (!v.isList()) failAt(v.at, d.path + ".children: expected a list of nodes, got " + v.kindName());
         d.children = &v;
       }},
  };
  return fields;
}

glm::dmat4 compose(const NodeDraft& d, const std::string& path) {
  if (d.matrix) {
    if (d.translate || d.rotate || d.scale)
      failAt(d.matrixAt, path + ".matrix: give either matrix or translate/rotate/scale, not both");
    return *d.matrix;
  }
  glm::dmat4 m(1.0);
  if (d.translate) m = glm::translate(m, *d.translate);
  if (d.rotate) m = m * *d.rotate;
  if (d.scale) m = glm::scale(m, *d.scale);
  return m;
}

// One mesh node's instance, as validateScene counts it: its mesh and a shadow proxy's.
std::string countInstance(const Scene& scene, const Node& node, ResourceBudget& budget) {
  const size_t meshCount = scene.meshes.size();
  if (node.mesh < 0 || size_t(node.mesh) >= meshCount) return {};
  const Mesh& mesh = *scene.meshes[size_t(node.mesh)];
  std::uint64_t triangles = mesh.triangles.size(), vertices = mesh.positions.size();
  if (node.castShadows && node.shadowProxy >= 0 && size_t(node.shadowProxy) < meshCount) {
    triangles += scene.meshes[size_t(node.shadowProxy)]->triangles.size();
    vertices += scene.meshes[size_t(node.shadowProxy)]->positions.size();
  }
  return budget.add(triangles, vertices);
}

// The generator's mesh nodes, counted first as validateScene does (nesting bounded by the
// generator's code); one beyond the budget is reported there, at the generator.
void countInstances(const Scene& scene, const Node& node, ResourceBudget& budget) {
  (void)countInstance(scene, node, budget);
  for (const Node& child : node.children) countInstances(scene, child, budget);
}

Node readNode(const YamlValue& map, const std::string& path, const Scene& scene, const NameIndex& index,
              Provenance& where) {
  if (!map.isMap()) failAt(map.at, path + ": expected a node (a map with name, mesh, translate, ...), got " + map.kindName());
  where.record(path, map.at);
  NodeDraft d;
  d.scene = &scene;
  d.index = &index;
  d.path = path;
  applyFields(map, path, nodeFields(), d, where);
  if (!d.nameGiven) d.node.name = d.node.mesh >= 0 ? scene.meshes[d.node.mesh]->name : "node";
  if (d.node.mesh >= 0 && index.instances) {
    if (const std::string exceeded = countInstance(scene, d.node, *index.instances); !exceeded.empty())
      failAt(map.at, path + ": " + exceeded);
  }
  if (d.children) {
    const std::string childPath = path + ".children.";
    for (size_t i = 0; i < d.children->items.size(); ++i)
      d.node.children.push_back(readNode(d.children->items[i], childPath + std::to_string(i), scene, index, where));
  }
  d.node.local = compose(d, path);
  // Each factor is bounded (kMaxSceneNumber), so T · R · S is too; a product that is not finite
  // would make the node vanish silently.
  if (!allWithin(d.node.local, kMaxWorldMagnitude))
    failAt(map.at, path + ": the node's transform is not finite (a translation, rotation or scale out of range)");
  return std::move(d.node);
}

}  // namespace

std::vector<Node> readNodeList(const YamlValue& list, size_t firstIndex, const Scene& scene,
                               const ResourceLimits& limits, Provenance& where) {
  NameIndex index(scene);
  ResourceBudget instances(limits);
  for (const Node& root : scene.roots) countInstances(scene, root, instances);  // a generator's nodes
  index.instances = &instances;
  std::vector<Node> nodes;
  nodes.reserve(list.items.size());
  for (size_t i = 0; i < list.items.size(); ++i)
    nodes.push_back(readNode(list.items[i], "nodes." + std::to_string(firstIndex + i), scene, index, where));
  return nodes;
}

glm::dmat4 readTransform(const YamlValue& map, const std::string& path) {
  static const Scene empty;
  static const NameIndex noNames(empty);
  Provenance ignored{map.at};
  NodeDraft d;
  d.scene = &empty;
  d.index = &noNames;
  std::vector<Field<NodeDraft>> transformOnly;
  for (const Field<NodeDraft>& f : nodeFields())
    if (f.key == "translate" || f.key == "rotate" || f.key == "scale" || f.key == "matrix") transformOnly.push_back(f);
  applyFields(map, path, transformOnly, d, ignored);
  return compose(d, path);
}

void applyNodeOverride(const YamlValue& map, Node& node, const std::string& path, const Scene& scene, Provenance& where) {
  const NameIndex index(scene);
  NodeDraft d;
  d.scene = &scene;
  d.index = &index;
  d.path = path;
  std::vector<Field<NodeDraft>> overridable;
  for (const Field<NodeDraft>& f : nodeFields())
    if (f.key == "cast_shadows" || f.key == "material" || f.key == "mesh" || f.key == "shadow_proxy")
      overridable.push_back(f);
  // The node's own fields, without its children: only the four keys above can change.
  d.node.mesh = node.mesh;
  d.node.material = node.material;
  d.node.castShadows = node.castShadows;
  d.node.shadowProxy = node.shadowProxy;
  applyFields(map, path, overridable, d, where);
  node.mesh = d.node.mesh;
  node.material = d.node.material;
  node.castShadows = d.node.castShadows;
  node.shadowProxy = d.node.shadowProxy;
}

}  // namespace shadowref
