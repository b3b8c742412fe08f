// The built-in primitives of the scene file: closed 2-manifolds, wound
// counter-clockwise seen from outside, centred at the origin with y up (except where noted), and
// already passed through buildAdjacency.
//
// Render normals are flat on planar faces (boxes, prisms, slabs, caps: vertices split at the
// crease) and smooth on curved sides. A position shared by several render vertices is computed once
// and copied, so the copies are bit-identical and weld (mesh.h).
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "scene/mesh.h"

namespace shadowref {

Mesh makeBox(const glm::dvec3& size);
// An axis-aligned box between two corners (not centred): walls, slabs, table tops.
Mesh makeBoxBetween(const glm::dvec3& min, const glm::dvec3& max);
Mesh makeSphere(double radius, int slices, int stacks);
Mesh makeCylinder(double radius, double height, int slices);
Mesh makeCone(double radius, double height, int slices);  // base at y = -height/2, apex at +height/2
// A ring around the y axis; genus 1, so V - E + F = 0.
Mesh makeTorus(double majorRadius, double minorRadius, int majorSegments, int minorSegments);
// A closed slab of size.x by size.y (in x and z) whose TOP face is at y = 0.
Mesh makePlane(const glm::dvec2& size, double thickness);
// A regular prism with `sides` sides around the y axis, circumradius `radius`.
Mesh makePrism(int sides, double radius, double height);
// A convex polygon given in the xz plane (x, z), extruded along y from -height/2 to +height/2.
Mesh makeExtrudedPolygon(const std::vector<glm::dvec2>& polygon, double height);

// A closed surface over a latitude/longitude grid: surface(theta, phi) with theta in [0, 2π)
// around the y axis and phi in [0, π] from the north pole (phi = 0) to the south pole (phi = π).
// The surface must be star-shaped around the origin; smooth normals from the faces.
template <class Surface>
Mesh makeLatLongSurface(const Surface& surface, int slices, int stacks);

// The grid behind makeSphere and makeLatLongSurface, exposed for shells with openings: the
// positions (north pole, rings 1 .. stacks-1 of `slices` vertices, south pole) and the index of
// grid vertex (ring, slice) — ring 0 is the north pole, ring `stacks` the south pole.
struct LatLongGrid {
  int slices = 0, stacks = 0;
  std::vector<glm::dvec3> positions;
  uint32_t at(int ring, int slice) const {
    if (ring <= 0) return 0;
    if (ring >= stacks) return static_cast<uint32_t>(positions.size() - 1);
    return 1 + static_cast<uint32_t>((ring - 1) * slices + ((slice % slices) + slices) % slices);
  }
};
template <class Surface>
LatLongGrid sampleLatLong(const Surface& surface, int slices, int stacks);

// The triangles of grid cell (ring, slice): the cell between rings `ring` and `ring + 1` and
// slices `slice` and `slice + 1`; one triangle at the poles, two elsewhere. Wound so that they face
// away from the origin.
void appendLatLongCell(const LatLongGrid& grid, int ring, int slice, std::vector<glm::uvec3>& out);

// Triangle (a, b, c) in the order whose normal points along `outward`.
glm::uvec3 orientTriangle(const std::vector<glm::dvec3>& positions, glm::uvec3 triangle,
                          const glm::dvec3& outward);

// --- template definitions ---

template <class Surface>
LatLongGrid sampleLatLong(const Surface& surface, int slices, int stacks) {
  constexpr double kPi = 3.14159265358979323846;
  LatLongGrid g;
  g.slices = slices;
  g.stacks = stacks;
  g.positions.push_back(surface(0.0, 0.0));
  for (int ring = 1; ring < stacks; ++ring) {
    const double phi = kPi * ring / stacks;
    for (int s = 0; s < slices; ++s) g.positions.push_back(surface(2.0 * kPi * s / slices, phi));
  }
  g.positions.push_back(surface(0.0, kPi));
  return g;
}

Mesh meshFromLatLongGrid(const LatLongGrid& grid);

template <class Surface>
Mesh makeLatLongSurface(const Surface& surface, int slices, int stacks) {
  return meshFromLatLongGrid(sampleLatLong(surface, slices, stacks));
}

}  // namespace shadowref
