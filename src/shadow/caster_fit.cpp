#include "shadow/caster_fit.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "gl/projection.h"
#include "shadow/focus_body.h"
#include "shadow/scene_passes.h"

namespace shadowref {

namespace {

Aabb inflated(const Aabb& box, double by) { return Aabb{box.min - glm::dvec3(by), box.max + glm::dvec3(by)}; }

// Light eye space bounds of points (x, y as they are; z negative in front of the light).
Aabb eyeBounds(const glm::dmat4& view, const glm::dvec3* points, size_t count) {
  Aabb b;
  for (size_t k = 0; k < count; ++k) b.add(glm::dvec3(view * glm::dvec4(points[k], 1.0)));
  return b;
}

// Whether a convex mesh drawn with `world` has a face turned from the light (n · d ≥ 0, grazing
// included) and towards `eye`: only there can it shadow itself.
bool facesItsOwnShadow(const Mesh& mesh, const glm::dmat4& world, bool mirrored, const glm::dvec3& d,
                       const glm::dvec3& eye) {
  for (const glm::uvec3& t : mesh.triangles) {
    const glm::dvec3 a(world * glm::dvec4(mesh.positions[t.x], 1.0));
    const glm::dvec3 b(world * glm::dvec4(mesh.positions[t.y], 1.0));
    const glm::dvec3 c(world * glm::dvec4(mesh.positions[t.z], 1.0));
    // Outward: counter-clockwise seen from outside; a mirroring transform flips the winding.
    const glm::dvec3 n = glm::cross(b - a, c - a) * (mirrored ? -1.0 : 1.0);
    if (glm::dot(n, d) >= 0.0 && glm::dot(n, eye - a) > 0.0) return true;
  }
  return false;
}

// Andrew's monotone chain: the convex hull of points, counter-clockwise, without collinear points.
std::vector<glm::dvec2> convexHull(std::vector<glm::dvec2> p) {
  std::sort(p.begin(), p.end(), [](const glm::dvec2& a, const glm::dvec2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  if (p.size() < 3) return p;
  auto cross = [](const glm::dvec2& o, const glm::dvec2& a, const glm::dvec2& b) {
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
  };
  std::vector<glm::dvec2> h(2 * p.size());
  size_t k = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0.0) --k;
    h[k++] = p[i];
  }
  for (size_t i = p.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(h[k - 2], h[k - 1], p[i]) <= 0.0) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);
  return h;
}

// The rotation about the light's axis (eye z) that turns `direction` (x, y) onto +x.
glm::dmat4 turnOntoX(const glm::dvec2& direction) {
  const glm::dvec2 u = glm::normalize(direction);
  glm::dmat4 r(1.0);
  r[0][0] = u.x, r[1][0] = u.y;
  r[0][1] = -u.y, r[1][1] = u.x;
  return r;
}

// The turn of the light view about its axis whose x-y bounding rectangle of the hull is smallest:
// one of the hull's edges lies along a side of the smallest rectangle ([Freeman & Shapira 1975]).
// Identity for fewer than three hull points or when no turn is smaller.
glm::dmat4 smallestRectangleTurn(const std::vector<glm::dvec2>& hull) {
  glm::dmat4 best(1.0);
  if (hull.size() < 3) return best;
  auto area = [&](const glm::dmat4& r) {
    glm::dvec2 lo(kInfinity), hi(-kInfinity);
    for (const glm::dvec2& p : hull) {
      const glm::dvec2 q(r * glm::dvec4(p, 0.0, 1.0));
      lo = glm::min(lo, q);
      hi = glm::max(hi, q);
    }
    return (hi.x - lo.x) * (hi.y - lo.y);
  };
  double bestArea = area(best);
  for (size_t i = 0; i < hull.size(); ++i) {
    const glm::dvec2 edge = hull[(i + 1) % hull.size()] - hull[i];
    if (!(glm::length(edge) > 0.0)) continue;
    const glm::dmat4 r = turnOntoX(edge);
    const double a = area(r);
    if (a < bestArea) bestArea = a, best = r;
  }
  return best;
}

}  // namespace

bool sweptBoxOverlaps(const Aabb& caster, const glm::dvec3& direction, const Aabb& receiver, double tolerance) {
  // The swept box meets the receiver iff the ray t · direction (t ≥ 0) meets the Minkowski
  // difference receiver − caster; overlapping by more than the tolerance: its open interior shrunk
  // by the tolerance.
  const glm::dvec3 lo = receiver.min - caster.max + glm::dvec3(tolerance);
  const glm::dvec3 hi = receiver.max - caster.min - glm::dvec3(tolerance);
  double tMin = 0.0, tMax = kInfinity;
  for (int a = 0; a < 3; ++a) {
    if (!(lo[a] < hi[a])) return false;
    if (direction[a] == 0.0) {
      if (!(lo[a] < 0.0 && 0.0 < hi[a])) return false;
      continue;
    }
    double t0 = lo[a] / direction[a], t1 = hi[a] / direction[a];
    if (t0 > t1) std::swap(t0, t1);
    tMin = std::max(tMin, t0);
    tMax = std::min(tMax, t1);
  }
  return tMin < tMax;
}

bool isConvexMesh(const Mesh& mesh) {
  if (mesh.topology != Topology::Closed || mesh.inconsistentEdges != 0 || mesh.triangles.empty() ||
      mesh.triangles.size() > kMaxConvexityTestTriangles)
    return false;
  const double size = glm::length(mesh.bounds.max - mesh.bounds.min);
  for (const glm::uvec3& t : mesh.triangles) {
    const glm::dvec3 a = mesh.positions[t.x];
    const glm::dvec3 n = glm::cross(mesh.positions[t.y] - a, mesh.positions[t.z] - a);
    const double length = glm::length(n);
    if (!(length > 0.0)) continue;  // a degenerate triangle has no plane to be behind
    for (const glm::dvec3& p : mesh.positions)
      if (glm::dot(n, p - a) / length > 1e-9 * size) return false;
  }
  return true;
}

CasterFit fitDirectionalToCasters(const Light& light, const std::vector<Instance>& instances, const Aabb& sceneBox,
                                  const std::array<glm::dvec3, 8>& frustum, const glm::dvec3& eye, int mapSize,
                                  int pcf) {
  CasterFit fit;
  fit.view = directionalLightView(light, sceneBox);
  if (sceneBox.empty()) return fit;
  const glm::dvec3 d = glm::normalize(light.direction);
  const glm::dmat4& V = fit.view.view;
  // Boxes of zero thickness (a flat mesh) have no volume to intersect; a tolerance far below any
  // texel keeps them.
  const double tolerance = 1e-9 * std::max(glm::length(sceneBox.max - sceneBox.min), 1.0);
  const ConvexBody frustumBody = hexahedron(frustum);
  const std::vector<glm::dvec3> visible = intersectionVertices({frustumBody, boxBody(inflated(sceneBox, tolerance))});
  if (visible.empty()) return fit;
  const Aabb visibleEye = eyeBounds(V, visible.data(), visible.size());

  // 1. The visible part of every instance's box (world bounds of box ∩ frustum), empty if none.
  std::vector<Aabb> seen(instances.size());
  for (size_t j = 0; j < instances.size(); ++j) {
    const Aabb& box = instances[j].worldBounds;
    if (box.empty()) continue;
    const std::vector<glm::dvec3> part = intersectionVertices({frustumBody, boxBody(inflated(box, tolerance))});
    Aabb b;
    for (const glm::dvec3& p : part) b.add(glm::clamp(p, box.min, box.max));
    seen[j] = b;
  }

  // 2. The casters that can shadow a visible part.
  std::map<const Mesh*, bool> convex;
  for (size_t i = 0; i < instances.size(); ++i) {
    const Instance& caster = instances[i];
    if (!caster.shadowMesh || caster.shadowBounds.empty() || !withinRange(light, caster.shadowBounds)) continue;
    const std::array<glm::dvec3, 8> corners = caster.shadowBounds.corners();
    const Aabb casterEye = eyeBounds(V, corners.data(), corners.size());
    // Nothing to shadow outside the visible part's rectangle.
    if (casterEye.min.x > visibleEye.max.x || casterEye.max.x < visibleEye.min.x || casterEye.min.y > visibleEye.max.y ||
        casterEye.max.y < visibleEye.min.y)
      continue;
    bool relevant = false;
    for (size_t j = 0; j < instances.size() && !relevant; ++j) {
      if (seen[j].empty()) continue;
      if (j != i) {
        relevant = sweptBoxOverlaps(caster.shadowBounds, d, seen[j], tolerance);
        continue;
      }
      if (caster.shadowMesh != caster.mesh) {
        relevant = true;  // a proxy: the visible mesh may stick out of it anywhere
        continue;
      }
      auto known = convex.find(caster.shadowMesh);
      if (known == convex.end()) known = convex.emplace(caster.shadowMesh, isConvexMesh(*caster.shadowMesh)).first;
      relevant = !known->second || facesItsOwnShadow(*caster.shadowMesh, caster.world, caster.mirrored, d, eye);
    }
    if (relevant) fit.casters.push_back(i);
  }
  if (fit.casters.empty()) return fit;

  // The light view turned about its axis so that the casters' footprint fills its rectangle best.
  std::vector<glm::dvec2> footprint;
  footprint.reserve(8 * fit.casters.size());
  for (const size_t i : fit.casters)
    for (const glm::dvec3& c : instances[i].shadowBounds.corners()) footprint.emplace_back(V * glm::dvec4(c, 1.0));
  fit.view.view = smallestRectangleTurn(convexHull(std::move(footprint))) * V;
  const glm::dmat4& turned = fit.view.view;
  const Aabb visibleTurned = eyeBounds(turned, visible.data(), visible.size());

  // Each caster's footprint cut to the visible rectangle; z: the casters' depths.
  Aabb mapEye;
  for (const size_t i : fit.casters) {
    const std::array<glm::dvec3, 8> corners = instances[i].shadowBounds.corners();
    const Aabb casterEye = eyeBounds(turned, corners.data(), corners.size());
    const glm::dvec2 lo = glm::max(glm::dvec2(casterEye.min), glm::dvec2(visibleTurned.min));
    const glm::dvec2 hi = glm::min(glm::dvec2(casterEye.max), glm::dvec2(visibleTurned.max));
    mapEye.add({lo.x, lo.y, casterEye.max.z});
    mapEye.add({std::max(hi.x, lo.x), std::max(hi.y, lo.y), casterEye.max.z});
  }

  // 3. The rectangle widened by the margin, the depths from the nearest caster (largest eye z) to
  // the farthest visible point.
  const double margin = double(kFitMarginTexels + pcf / 2);
  const double scale = double(mapSize) / std::max(double(mapSize) - 2.0 * margin, 1.0);
  glm::dvec2 centre = 0.5 * (glm::dvec2(mapEye.min) + glm::dvec2(mapEye.max));
  glm::dvec2 half = 0.5 * (glm::dvec2(mapEye.max) - glm::dvec2(mapEye.min)) * scale;
  const double minHalf = tolerance;  // a caster seen edge-on from the light still gets a map
  half = glm::max(half, glm::dvec2(minHalf));
  const double nearest = -mapEye.max.z, farthest = -visibleTurned.min.z;
  const double depth = std::max(farthest - nearest, tolerance);
  LightView& v = fit.view;
  v.nearPlane = nearest - kLightDepthMargin * depth;
  v.farPlane = farthest + kLightDepthMargin * depth;
  v.projection = ortho(centre.x - half.x, centre.x + half.x, centre.y - half.y, centre.y + half.y, v.nearPlane, v.farPlane);
  fit.fitted = true;
  return fit;
}

}  // namespace shadowref
