// The `nodes:` section: the scene graph ([Kuhn 2016, §4.1.1]). Each node has a name, optionally a
// mesh and a material (by name), a transform — translate/rotate/scale, or a matrix — shadow flags
// and children.
#pragma once

#include <string>

#include "scene/scene.h"
#include "scene/yaml_fields.h"

namespace shadowref {

// Reads one node (and its children). Meshes and materials are looked up by name in `scene`.
Node readNode(const YamlValue& map, const std::string& path, const Scene& scene, Provenance& where);

// The transform keys alone, for tests and overrides: local = T · R · S (scale first, then rotate,
// then translate), or `matrix`. Throws for a singular result.
glm::dmat4 readTransform(const YamlValue& map, const std::string& path);

}  // namespace shadowref
