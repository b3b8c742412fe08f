// The `nodes:` section: the scene graph ([Kuhn 2016, §4.1.1]). Each node has a name, optionally a
// mesh and a material (by name), a transform — translate/rotate/scale, or a matrix — shadow flags
// and children.
#pragma once

#include <string>
#include <vector>

#include "scene/resource_limits.h"
#include "scene/scene.h"
#include "scene/yaml_fields.h"

namespace shadowref {

// Reads a list of nodes (and their children), the first named "nodes.<firstIndex>". Meshes and
// materials are looked up by name in `scene`, through a hash index built once for the list (a
// scene of n nodes and m meshes costs O(n + m), not O(n * m)). Each node's location is recorded in
// `where` under its path, for the checks made on the finished scene (world transforms, budget).
// Mesh nodes are counted against the resource budget as they are read, so that a file whose
// aliases repeat a mesh a million times is rejected at the first node too many, not after reading
// them all.
std::vector<Node> readNodeList(const YamlValue& list, size_t firstIndex, const Scene& scene,
                               const ResourceLimits& limits, Provenance& where);

// -D nodes.PATH.KEY=value on a node of the finished scene: the keys cast_shadows, material, mesh
// and shadow_proxy of `map`, checked as in a file (names looked up in `scene`). Another key is an
// error that lists these; the transform and the children stay as the file made them.
void applyNodeOverride(const YamlValue& map, Node& node, const std::string& path, const Scene& scene, Provenance& where);

// The transform keys alone, for tests and overrides: local = T · R · S (scale first, then rotate,
// then translate), or `matrix`. Throws for a singular result.
glm::dmat4 readTransform(const YamlValue& map, const std::string& path);

}  // namespace shadowref
