#include "scene/pumpkin.h"

#include <cmath>
#include <set>
#include <utility>
#include <vector>

#include "scene/adjacency.h"
#include "scene/primitives.h"

namespace shadowref {

namespace {

// Radius modulated by the ribs, flattened to `squash`, with dimples at the stem and the bottom.
auto pumpkinSurface(const PumpkinShape& s) {
  return [s](double theta, double phi) {
    const double groove = 0.5 - 0.5 * std::cos(s.ribs * theta);
    const double r = s.radius * (1.0 - s.ribDepth * groove);
    const double top = std::exp(-(phi / 0.45) * (phi / 0.45));
    const double bottom = std::exp(-((3.14159265358979323846 - phi) / 0.45) * ((3.14159265358979323846 - phi) / 0.45));
    const double y = s.radius * (s.squash * std::cos(phi) - 0.12 * top + 0.08 * bottom);
    return glm::dvec3(r * std::sin(phi) * std::cos(theta), y, r * std::sin(phi) * std::sin(theta));
  };
}

// Which grid cells (ring, slice) of the lantern are cut away. Slice 0 looks along +x. Every opening
// is a union of whole cells whose rows overlap by at least one cell, so its border is one simple
// loop of grid edges (no two openings touch, not even at a corner).
bool isOpening(int ring, int slice, int slices, int stacks) {
  // Signed slice offset from the face's centre line.
  int d = slice % slices;
  if (d > slices / 2) d -= slices;
  const int equator = stacks / 2;
  const int lidRings = std::max(1, stacks / 8);
  if (ring < lidRings) return true;                         // the lid
  const int eyeRow = ring - (equator - 5);                   // rows 0, 1, 2 above the equator
  if (eyeRow >= 0 && eyeRow < 3) {                           // eyes: triangles, apex up
    const int halfWidth = eyeRow;                            // 1, 3, 5 cells wide
    if (std::abs(d - (-3)) <= halfWidth && d < 0) return true;
    if (std::abs(d - 3) <= halfWidth && d > 0) return true;
  }
  const int mouthRow = ring - (equator + 2);                 // two rows below the equator
  if (mouthRow == 0) return std::abs(d) <= 5 && d != 0;      // the tooth hangs from the top
  if (mouthRow == 1) return std::abs(d) <= 5;
  return false;
}

}  // namespace

Mesh makePumpkin(const PumpkinShape& shape) {
  Mesh m = makeLatLongSurface(pumpkinSurface(shape), shape.slices, shape.stacks);
  m.name = "pumpkin";
  return m;
}

Mesh makeHollowPumpkin(const PumpkinShape& shape, double wallThickness) {
  const LatLongGrid outer = sampleLatLong(pumpkinSurface(shape), shape.slices, shape.stacks);
  const uint32_t n = static_cast<uint32_t>(outer.positions.size());
  const double inset = 1.0 - wallThickness / shape.radius;  // the inner skin: the outer one, scaled

  // The outer skin without the openings.
  std::vector<glm::uvec3> skin;
  for (int ring = 0; ring < shape.stacks; ++ring)
    for (int s = 0; s < shape.slices; ++s)
      if (!isOpening(ring, s, shape.slices, shape.stacks)) appendLatLongCell(outer, ring, s, skin);

  Mesh mesh;
  mesh.name = "pumpkin_lantern";
  // Render vertices 0 .. n-1: outer skin, smooth; n .. 2n-1: inner skin, normals turned inwards.
  {
    Mesh smooth;
    smooth.positions = outer.positions;
    for (int ring = 0; ring < shape.stacks; ++ring)
      for (int s = 0; s < shape.slices; ++s) appendLatLongCell(outer, ring, s, smooth.triangles);
    computeSmoothNormals(smooth);
    mesh.positions = outer.positions;
    mesh.normals = smooth.normals;
    for (uint32_t i = 0; i < n; ++i) {
      mesh.positions.push_back(outer.positions[i] * inset);
      mesh.normals.push_back(-smooth.normals[i]);
    }
  }
  for (const glm::uvec3& t : skin) {
    mesh.triangles.push_back(t);
    mesh.triangles.push_back(glm::uvec3(t.x, t.z, t.y) + n);  // inner: same cell, facing the cavity
  }

  // Rims: every border edge a -> b of the outer skin (its reverse b -> a belongs to no kept
  // triangle) is joined to its inner copy by the quad (b, a, a', b'), which runs the outer edge
  // b -> a and the inner edge a' -> b' opposite to the skins, keeping the shell consistently wound.
  std::set<std::pair<uint32_t, uint32_t>> directed;
  for (const glm::uvec3& t : skin)
    for (int i = 0; i < 3; ++i) directed.insert({t[i], t[(i + 1) % 3]});
  for (const glm::uvec3& t : skin)
    for (int i = 0; i < 3; ++i) {
      const uint32_t a = t[i], b = t[(i + 1) % 3];
      if (directed.count({b, a})) continue;
      const glm::dvec3 q[4] = {mesh.positions[b], mesh.positions[a], mesh.positions[a + n], mesh.positions[b + n]};
      const glm::dvec3 normal = glm::normalize(glm::cross(q[1] - q[0], q[2] - q[0]));
      const uint32_t base = static_cast<uint32_t>(mesh.positions.size());
      for (const glm::dvec3& p : q) {
        mesh.positions.push_back(p);  // copies: bit-identical, so they weld with the skins
        mesh.normals.push_back(normal);
      }
      mesh.triangles.push_back({base, base + 1, base + 2});
      mesh.triangles.push_back({base, base + 2, base + 3});
    }
  buildAdjacency(mesh);
  return mesh;
}

}  // namespace shadowref
