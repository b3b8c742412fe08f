#include "scene/scene_info.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "scene/adjacency.h"
#include "scene/animation.h"
#include "scene/scene_sections.h"

namespace shadowref {

namespace {

std::string num(double x) {
  if (x == kInfinity) return "infinite";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

std::string vec(const glm::dvec3& v) {
  std::string s = "(";
  s += num(v.x);
  s += ", ";
  s += num(v.y);
  s += ", ";
  s += num(v.z);
  s += ")";
  return s;
}

std::string box(const Aabb& b) { return b.empty() ? std::string("empty") : vec(b.min) + " .. " + vec(b.max); }

Aabb transformed(const Aabb& b, const glm::dmat4& m) {
  Aabb out;
  if (b.empty()) return out;
  for (int i = 0; i < 8; ++i) {
    const glm::dvec3 c((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y, (i & 4) ? b.max.z : b.min.z);
    out.add(glm::dvec3(m * glm::dvec4(c, 1.0)));
  }
  return out;
}

const char* topologyName(Topology t) {
  switch (t) {
    case Topology::Closed: return "closed";
    case Topology::Open: return "open";
    case Topology::NonManifold: return "non-manifold";
  }
  return "?";
}

// How the mesh is wound: inconsistently (neighbours disagree on inside and outside), or for a
// consistently wound closed mesh the signed volume it encloses, negative when it is inside out.
std::string winding(const Mesh& m) {
  if (m.inconsistentEdges > 0)
    return ", inconsistently wound (" + std::to_string(m.inconsistentEdges) +
           " edges whose two triangles run them the same way)";
  if (m.topology != Topology::Closed) return "";
  std::string parts;
  if (m.mixedWinding) {
    const ClosedPartWinding w = closedPartWinding(m);
    parts = " (partly inside out: " + std::to_string(w.insideOut) + " of its " + std::to_string(w.parts) +
            " closed parts enclose a negative volume outside every other part)";
  }
  return ", encloses volume " + num(m.enclosedVolume) +
         (m.insideOut ? " (negative: inside out, every triangle wound clockwise seen from outside)" : "") + parts;
}

std::string meshName(const Scene& scene, int index) {
  return index >= 0 && index < static_cast<int>(scene.meshes.size()) ? scene.meshes[index]->name : "?";
}

void describeNode(std::ostringstream& out, const Scene& scene, const Node& node, const glm::dmat4& parent,
                  int depth, Aabb& sceneBounds) {
  const glm::dmat4 world = parent * node.local;
  out << std::string(2 + 2 * depth, ' ') << node.name;
  if (node.mesh >= 0 && node.mesh < static_cast<int>(scene.meshes.size())) {
    const Aabb bounds = transformed(scene.meshes[node.mesh]->bounds, world);
    if (!bounds.empty()) sceneBounds.add(bounds.min), sceneBounds.add(bounds.max);
    out << "  mesh " << meshName(scene, node.mesh);
    if (node.material >= 0 && node.material < static_cast<int>(scene.materials.size()))
      out << ", material " << scene.materials[node.material].name;
    if (!node.castShadows) out << ", casts no shadow";
    else if (node.shadowProxy >= 0) out << ", shadow proxy " << meshName(scene, node.shadowProxy);
    out << ", world bounds " << box(bounds);
  }
  out << "\n";
  for (const Node& child : node.children) describeNode(out, scene, child, world, depth + 1, sceneBounds);
}

void describeLight(std::ostringstream& out, const Light& l) {
  out << "  " << l.name << ": " << enumName(lightTypeNames(), l.type);
  if (l.type != LightType::Directional) out << " at " << vec(l.position);
  if (l.type != LightType::Point) out << " direction " << vec(l.direction);
  out << ", color " << vec(l.color) << ", range " << num(l.range);
  if (l.type == LightType::Spot) out << ", cutoff " << num(l.spotCutoffDegrees) << " deg, exponent " << num(l.spotExponent);
  if (l.attenuation != glm::dvec3(1.0, 0.0, 0.0)) out << ", attenuation " << vec(l.attenuation);
  if (l.soft != SoftShape::None) out << ", soft " << enumName(softShapeNames(), l.soft) << " spacing " << num(l.softSpacing);
  out << "\n";
}

}  // namespace

std::string describeScene(const Scene& scene, std::string_view shadowDetails) {
  std::ostringstream out;
  out << "scene: " << scene.sourceFile << "\n";
  out << "image: " << scene.width << " x " << scene.height << ", depth " << enumName(depthFormatNames(), scene.depthFormat)
      << "\n";
  const Camera& c = scene.camera;
  out << "camera: eye " << vec(c.eye) << ", target " << vec(c.target) << ", up " << vec(c.up) << ", fov "
      << num(c.fovYDegrees) << " deg, near " << num(c.nearPlane) << ", far " << num(c.farPlane) << "\n";
  out << "ambient " << vec(scene.ambient) << ", background " << vec(scene.background) << "\n";
  out << "shadow: " << scene.shadow.method << (shadowDetails.empty() ? "" : ", ") << shadowDetails << "\n";

  out << "lights (" << scene.lights.size() << "):\n";
  for (const Light& l : scene.lights) describeLight(out, l);

  out << "materials (" << scene.materials.size() << "):\n";
  for (const Material& m : scene.materials)
    out << "  " << m.name << ": ambient " << vec(m.ambient) << ", diffuse " << vec(m.diffuse) << ", specular "
        << vec(m.specular) << ", shininess " << num(m.shininess) << ", " << enumName(shadingNames(), m.shading)
        << (m.blinn ? ", blinn" : "") << "\n";

  size_t triangles = 0;
  out << "meshes (" << scene.meshes.size() << "):\n";
  for (const auto& m : scene.meshes) {
    triangles += m->triangles.size();
    out << "  " << m->name << ": " << m->triangles.size() << " triangles, " << m->weldedPositions.size()
        << " welded vertices, " << m->edges.size() << " edges, " << topologyName(m->topology) << " (" << m->openEdges
        << " open, " << m->nonManifoldEdges << " non-manifold edges)" << winding(*m) << ", bounds " << box(m->bounds)
        << "\n";
  }

  out << "nodes:\n";
  Aabb sceneBounds;
  for (const Node& root : scene.roots) describeNode(out, scene, root, glm::dmat4(1.0), 0, sceneBounds);

  size_t instances = 0, instanceTriangles = 0;
  for (const Instance& inst : scene.instances()) ++instances, instanceTriangles += inst.mesh->triangles.size();
  out << "total: " << instances << " instances, " << instanceTriangles << " triangles drawn (" << triangles
      << " in distinct meshes), world bounds " << box(sceneBounds) << "\n";
  if (const Animation* a = scene.animation.get())
    out << "animation: " << num(a->fps) << " fps, keys up to t = " << num(a->lastKeyTime()) << " s (frame "
        << num(std::ceil(a->lastKeyTime() * a->fps)) << "); " << (a->camera.eye || a->camera.target || a->camera.fov ? "camera, " : "")
        << a->lights.size() << (a->lights.size() == 1 ? " light, " : " lights, ") << a->nodes.size()
        << (a->nodes.size() == 1 ? " node" : " nodes") << " animated (above: the values as "
        << "written, which the tracks replace in each frame)\n";
  return out.str();
}

}  // namespace shadowref
