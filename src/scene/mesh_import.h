// Mesh files: Wavefront OBJ (tinyobjloader) and glTF 2.0 (tinygltf), read into one
// triangle mesh each, triangulated, with normals computed where the file has none, welded and with
// adjacency built (adjacency.h). Every failure throws SceneError naming the file, and the line and
// column where the format has them.
#pragma once

#include <string>
#include <vector>

#include "scene/mesh.h"

namespace shadowref {

// All shapes of the file merged into one mesh. Indices are checked before tinyobjloader sees the
// file (it accepts some out-of-range indices silently), so a bad index is reported with its line
// and column. `warnings` receives dropped degenerate triangles and the loader's own warnings.
Mesh loadObj(const std::string& path, std::vector<std::string>* warnings = nullptr);

// Every triangle primitive (TRIANGLES, TRIANGLE_STRIP, TRIANGLE_FAN) of every mesh reachable from
// the default scene (or, without scenes, from every root node), with the node transforms applied.
// .glb files are read as binary, everything else as JSON.
Mesh loadGltf(const std::string& path, std::vector<std::string>* warnings = nullptr);

}  // namespace shadowref
