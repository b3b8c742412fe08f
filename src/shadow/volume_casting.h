// How the shadow volumes treat a mesh that is not a closed, consistently wound, outward surface.
//
// The silhouette volume ([Kuhn 2016, §3.4, §3.5]) is exact only for a closed 2-manifold whose
// triangles are wound counter-clockwise seen from outside; [Everitt & Kilgard 2002] and
// [McGuire et al. 2003] make that a requirement of robust volumes. Meshes users write are often
// not: a tent of two roof quads without a floor is open, a fin of three triangles on one edge is
// non-manifold, an OBJ exported with the other handedness is inside out. Such a mesh is cast as
// follows, so that every counting method gives the same, right count:
//
//  - Silhouette: closed, consistently wound, enclosing a positive volume. The volume of the
//    documents, built by the chosen silhouette algorithm (silhouette.h).
//  - Reversed: closed and consistently wound but inside out (Mesh::insideOut, a negative enclosed
//    volume). The winding is taken as reversed: the triangles whose INWARD normal faces the light
//    are the front cap, turned round, and the volume is the silhouette volume of the mesh as it
//    should have been wound.
//  - TwoSided: open, non-manifold or inconsistently wound, or closed with some of its closed parts
//    inside out and others not (Mesh::mixedWinding: no one winding holds for the whole mesh, and
//    a silhouette volume of an inside-out part left as it is misses its shadow). There is no
//    inside to rely on, so the mesh casts its shadow as a two-sided surface: a point is in shadow
//    when the segment to the light meets any triangle, whichever way it faces. The volume is the union of one closed volume per
//    triangle ([Crow 1977]: a polygon's shadow volume; each triangle turned to face the light:
//    the triangle as front cap, its three edges extruded, the triangle at infinity as back cap),
//    counted with signs: where two such volumes share a side with opposite orientation the two
//    sides cancel and neither is drawn, so the sides that remain are the edges whose signed count
//    of light-facing triangles is not zero, each drawn |count| times (an open edge once, the
//    ridge of a tent lit from one side twice). Counting edges with multiplicity for models that
//    are not closed 2-manifolds is discussed by [Bergeron 1986] and [Aldridge & Woods 2004]. The
//    stencil count at a point is then the number of triangles between it and the light.
//
// In the Reversed and TwoSided cases the scene pass, which culls back faces by the winding the
// file gave, can show the back of a front-cap triangle: the inside of an open roof, the near wall
// of an inside-out box. A ray through it leaves a volume through its front cap before reaching
// the surface it hits, and z-pass, which draws no caps for closed meshes, would miss that exit
// (a false shadow beside the tent). So for these meshes z-pass draws the front cap too
// (ShadowVolume::casting, shadow_volume.h): every face of a closed volume is then counted by
// z-pass in front of the surface or by z-fail behind it, and the two agree wherever the camera is
// outside every volume.
#pragma once

#include <cstdint>
#include <string>

#include "scene/mesh.h"

namespace shadowref {

enum class VolumeCasting : uint8_t { Silhouette, Reversed, TwoSided };

VolumeCasting volumeCastingOf(const Mesh& mesh);

// What `render` prints once for a mesh the volumes do not cast as it is: what is wrong with it
// and what is done about it, naming the mesh. Empty for a Silhouette mesh.
std::string castingWarning(const Mesh& mesh);

}  // namespace shadowref
