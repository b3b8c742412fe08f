// The `meshes:` section: one mesh per name, from a built-in primitive or a file (OBJ, glTF) whose
// path is relative to the scene file's folder.
#pragma once

#include <memory>
#include <string>

#include "scene/mesh.h"
#include "scene/yaml_fields.h"

namespace shadowref {

// Limits on tessellation counts in a scene file: enough for any picture, small enough that a
// typo cannot ask for billions of triangles.
inline constexpr int kMaxSegments = 1024;
inline constexpr long long kMaxGridCells = 1LL << 18;       // slices x stacks of a sphere or torus
inline constexpr size_t kMaxSceneFileTriangles = 1u << 23;  // all meshes of the meshes section

// Builds the mesh described by `source` (a map with one key: box, sphere, cylinder, cone, torus,
// plane, prism, obj or gltf). Errors: unknown kind, bad parameters, a missing or unreadable file
// (at the path's location), errors inside the file (at the file's own line), no triangles.
std::shared_ptr<Mesh> readMeshSource(const YamlValue& source, const std::string& name, const std::string& path,
                                     const std::string& baseDir, Provenance& where);

}  // namespace shadowref
