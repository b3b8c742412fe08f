// Mesh files: Wavefront OBJ (obj_import.cpp) and glTF 2.0 (gltf_import.cpp), read into
// one triangle mesh each, triangulated, with normals computed where the file has none, welded and
// with adjacency built (adjacency.h). Every failure throws SceneError naming the file, and the line
// and column where the format has them (for .glb, which has no lines, the byte offset).
// Files are opened only when regular and at most kMaxInputFileBytes long (input_file.h).
#pragma once

#include <string>
#include <vector>

#include "scene/mesh.h"

namespace shadowref {

// All faces of the file merged into one mesh, read by our own parser (positions `v`, normals `vn`
// and faces `f`; texture coordinates are checked but not used; everything else, materials
// included, is ignored and no other file is opened). Numbers are decimal; every face index must
// name an existing vertex. Faces are triangulated in linear time when convex (a quad along its
// shorter diagonal, larger faces as a fan); non-convex faces of up to kMaxNonConvexCorners corners
// by ear clipping, larger ones are an error. `warnings` receives dropped degenerate triangles.
Mesh loadObj(const std::string& path, std::vector<std::string>* warnings = nullptr);
inline constexpr size_t kMaxNonConvexCorners = 256;

// Every triangle primitive (TRIANGLES, TRIANGLE_STRIP, TRIANGLE_FAN) of every mesh reachable from
// the default scene (or, without scenes, from every root node), with the node transforms applied.
// .glb files are read as binary, everything else as JSON. Images are never loaded. The node
// hierarchy must be a set of strict trees (glTF 2.0 §3.5.3) and expand to at most
// kMaxGltfTriangles triangles.
Mesh loadGltf(const std::string& path, std::vector<std::string>* warnings = nullptr);
inline constexpr size_t kMaxGltfTriangles = size_t{1} << 23;

// Shared by both importers: rejects non-finite positions and meshes without triangles, normalises
// the file's normals (or computes crease normals when any is missing or zero), welds and builds
// adjacency.
Mesh finishImportedMesh(Mesh mesh, bool haveNormals, const std::string& path, std::vector<std::string>* warnings);

}  // namespace shadowref
