// Welding and the edge list of a mesh ([Kuhn 2016, §4.3.5]): what the silhouette algorithms
// need — every edge with its two vertices and the triangles on either side.
#pragma once

#include <string>
#include <vector>

#include "scene/mesh.h"

namespace shadowref {

// Fills the welded view of `mesh` from its render view:
//  - welds render vertices whose positions are bit-for-bit equal (-0.0 counts as +0.0);
//  - drops degenerate triangles (two equal welded corners, or zero area) from BOTH views and
//    appends one warning per dropped triangle to `warnings` when given;
//  - builds the edge list in O(n) with a hash map keyed by the unordered welded vertex pair,
//    edges in order of first appearance, v0 -> v1 as the edge runs in t0 ([Kuhn 2016, §4.3.5]);
//  - records each triangle's three edges (triangleEdges);
//  - counts open (1 triangle), non-manifold (>= 3) and inconsistently wound edges and sets the
//    topology;
//  - the signed enclosed volume, and whether a closed, consistently wound mesh is inside out;
//  - face normals from the welded positions, object-space bounds.
// weldedPositions holds every distinct render position, also those used only by dropped triangles.
void buildAdjacency(Mesh& mesh, std::vector<std::string>* warnings = nullptr);

// Render normals for meshes that come without them (imports, generated surfaces).
// Flat: every triangle gets three vertices of its own with the face normal.
void computeFlatNormals(Mesh& mesh);
// Smooth: each render vertex gets the area-weighted average of the face normals of all triangles
// touching its position. Render vertices are kept as they are (share them for a smooth surface).
void computeSmoothNormals(Mesh& mesh);
// Smooth within a crease angle: each triangle corner averages the face normals around its position
// whose angle to the triangle's own normal is at most `creaseDegrees`; corners with equal position
// and equal normal share one render vertex. Sharp edges stay sharp, curved surfaces look smooth.
void computeCreaseNormals(Mesh& mesh, double creaseDegrees = 40.0);

// Signed volume enclosed by the welded triangles (divergence theorem): positive when a closed
// mesh is wound counter-clockwise seen from outside.
double signedVolume(const Mesh& mesh);

// The closed parts of a closed, consistently wound mesh (its triangles connected across edges)
// and how many of them are inside out: enclosing a clearly negative signed volume while lying
// inside an even number of the other parts (none, for a part on its own). A part inside an odd
// number of others is a cavity, and a negative volume is its right winding. The enclosure is
// the generalized winding number of the part's first triangle's centroid with respect to each
// other part, |w| > 1/2 (the solid angles of [Van Oosterom & Strackee 1983]); it is computed for
// the negative parts only, so a mesh without one costs a union-find over its edges; beyond the
// first kMaxEnclosureTests negative parts (each test costs every triangle) the rest are counted as
// inside out, which at worst casts a mesh of many cavities two-sided: right, if slower.
inline constexpr size_t kMaxEnclosureTests = 64;
struct ClosedPartWinding {
  size_t parts = 0, insideOut = 0;
};
ClosedPartWinding closedPartWinding(const Mesh& mesh);

}  // namespace shadowref
