#include "scene/scene.h"

namespace shadowref {

namespace {

Aabb transformBounds(const Aabb& box, const glm::dmat4& m) {
  Aabb out;
  if (box.empty()) return out;
  // The eight corners, transformed: exact for any affine map, conservative box around the result.
  for (int i = 0; i < 8; ++i) {
    const glm::dvec3 c((i & 1) ? box.max.x : box.min.x, (i & 2) ? box.max.y : box.min.y,
                       (i & 4) ? box.max.z : box.min.z);
    const glm::dvec4 p = m * glm::dvec4(c, 1.0);
    out.add(glm::dvec3(p) / p.w);
  }
  return out;
}

// [Kuhn 2016, §4.1.1]: the scene graph, flattened depth-first; a child's world matrix is parent *
// local.
void flatten(const Scene& scene, const Node& node, const glm::dmat4& parent, const std::string& parentPath,
             std::vector<Instance>& out) {
  const glm::dmat4 world = parent * node.local;
  const std::string path = parentPath.empty() ? node.name : parentPath + "/" + node.name;
  if (node.mesh >= 0 && node.mesh < static_cast<int>(scene.meshes.size())) {
    Instance inst;
    inst.path = path;
    inst.mesh = scene.meshes[node.mesh].get();
    if (node.castShadows) {
      const bool proxy = node.shadowProxy >= 0 && node.shadowProxy < static_cast<int>(scene.meshes.size());
      inst.shadowMesh = proxy ? scene.meshes[node.shadowProxy].get() : inst.mesh;
    }
    inst.world = world;
    inst.material = node.material;
    inst.worldBounds = transformBounds(inst.mesh->bounds, world);
    // The usual caster is its own shadow mesh: its bounds are the ones just made (the city's
    // frames flatten 129 instances each).
    inst.shadowBounds = !inst.shadowMesh                ? Aabb{}
                        : inst.shadowMesh == inst.mesh ? inst.worldBounds
                                                       : transformBounds(inst.shadowMesh->bounds, world);
    inst.mirrored = glm::determinant(glm::dmat3(world)) < 0.0;
    out.push_back(std::move(inst));
  }
  for (const Node& child : node.children) flatten(scene, child, world, path, out);
}

}  // namespace

Aabb worldBounds(const std::vector<Instance>& instances) {
  Aabb box;
  for (const Instance& inst : instances) {
    if (inst.worldBounds.empty()) continue;
    box.add(inst.worldBounds.min);
    box.add(inst.worldBounds.max);
  }
  return box;
}

std::vector<Instance> Scene::instances() const {
  std::vector<Instance> out;
  const std::string rootPath;
  for (const Node& root : roots) flatten(*this, root, glm::dmat4(1.0), rootPath, out);
  return out;
}

}  // namespace shadowref
