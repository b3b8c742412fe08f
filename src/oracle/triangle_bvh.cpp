#include "oracle/triangle_bvh.h"

#include <algorithm>
#include <cmath>

namespace shadowref::oracle {

namespace {

constexpr uint32_t kLeafSize = 4;
constexpr double kBarycentricSlack = 1e-10;

glm::dvec3 centroid(const BvhTriangle& t) { return (t.a + t.b + t.c) / 3.0; }

// Slab test; the ray may run parallel to a slab (1/0 = inf handles it, 0 * inf is avoided by
// computing with the reciprocal only where the component is non-zero).
bool hitsBox(const Aabb& box, const glm::dvec3& origin, const glm::dvec3& direction, double tMin, double tMax) {
  for (int i = 0; i < 3; ++i) {
    if (direction[i] == 0.0) {
      if (origin[i] < box.min[i] || origin[i] > box.max[i]) return false;
      continue;
    }
    const double inv = 1.0 / direction[i];
    double t0 = (box.min[i] - origin[i]) * inv, t1 = (box.max[i] - origin[i]) * inv;
    if (t0 > t1) std::swap(t0, t1);
    tMin = std::max(tMin, t0);
    tMax = std::min(tMax, t1);
    if (tMin > tMax) return false;
  }
  return true;
}

bool closerTie(const BvhTriangle& a, const BvhTriangle& b) {
  return a.instance != b.instance ? a.instance < b.instance : a.triangle < b.triangle;
}

}  // namespace

bool intersectTriangle(const BvhTriangle& tri, const glm::dvec3& origin, const glm::dvec3& direction,
                       double tMin, double tMax, double& t) {
  const glm::dvec3 e1 = tri.b - tri.a, e2 = tri.c - tri.a;
  const glm::dvec3 p = glm::cross(direction, e2);
  const double det = glm::dot(e1, p);
  if (det == 0.0) return false;
  const double inv = 1.0 / det;
  const glm::dvec3 s = origin - tri.a;
  const double u = glm::dot(s, p) * inv;
  if (u < -kBarycentricSlack || u > 1.0 + kBarycentricSlack) return false;
  const glm::dvec3 q = glm::cross(s, e1);
  const double v = glm::dot(direction, q) * inv;
  if (v < -kBarycentricSlack || u + v > 1.0 + kBarycentricSlack) return false;
  t = glm::dot(e2, q) * inv;
  return t >= tMin && t <= tMax;
}

TriangleBvh::TriangleBvh(std::vector<BvhTriangle> triangles) : triangles_(std::move(triangles)) {
  if (!triangles_.empty()) build(0, static_cast<uint32_t>(triangles_.size()));
}

uint32_t TriangleBvh::build(uint32_t first, uint32_t count) {
  const uint32_t index = static_cast<uint32_t>(nodes_.size());
  nodes_.emplace_back();
  Aabb bounds, centres;
  for (uint32_t i = first; i < first + count; ++i) {
    const BvhTriangle& t = triangles_[i];
    bounds.add(t.a);
    bounds.add(t.b);
    bounds.add(t.c);
    centres.add(centroid(t));
  }
  // Padded, so the barycentric slack of intersectTriangle never reaches outside a node's box.
  const glm::dvec3 pad = (bounds.max - bounds.min) * 1e-9 + 1e-12 * (glm::abs(bounds.min) + glm::abs(bounds.max));
  bounds.min -= pad;
  bounds.max += pad;
  nodes_[index].bounds = bounds;
  const glm::dvec3 extent = centres.max - centres.min;
  if (count <= kLeafSize || std::max({extent.x, extent.y, extent.z}) == 0.0) {
    nodes_[index].first = first;
    nodes_[index].count = count;
    return index;
  }
  const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
  const auto begin = triangles_.begin() + first;
  const auto middle = begin + count / 2;
  std::nth_element(begin, middle, begin + count, [axis](const BvhTriangle& a, const BvhTriangle& b) {
    const double ca = centroid(a)[axis], cb = centroid(b)[axis];
    return ca != cb ? ca < cb : closerTie(a, b);
  });
  const uint32_t left = build(first, count / 2);
  const uint32_t right = build(first + count / 2, count - count / 2);
  nodes_[index].left = left;
  nodes_[index].right = right;
  return index;
}

// One traversal for both queries, left child first. firstHit's visit lowers tMax to the nearest
// hit so far, so the boxes still on the stack are tested against the shorter ray.
template <class Visit>
void TriangleBvh::traverse(const glm::dvec3& origin, const glm::dvec3& direction, double tMin, const double& tMax,
                           Visit&& visit) const {
  if (nodes_.empty()) return;
  std::vector<uint32_t> stack{0};
  while (!stack.empty()) {
    const Node& n = nodes_[stack.back()];
    stack.pop_back();
    if (!hitsBox(n.bounds, origin, direction, tMin, tMax)) continue;
    if (n.count == 0) {
      stack.push_back(n.right);
      stack.push_back(n.left);
      continue;
    }
    for (uint32_t i = n.first; i < n.first + n.count; ++i)
      if (visit(triangles_[i])) return;
  }
}

RayHit TriangleBvh::firstHit(const glm::dvec3& origin, const glm::dvec3& direction, double tMin, double tMax) const {
  RayHit best;
  const BvhTriangle* bestTri = nullptr;
  traverse(origin, direction, tMin, tMax, [&](const BvhTriangle& tri) {
    double t = 0.0;
    if (tri.backCulled && glm::dot(glm::cross(tri.b - tri.a, tri.c - tri.a), direction) >= 0.0) return false;
    if (!intersectTriangle(tri, origin, direction, tMin, tMax, t)) return false;
    if (bestTri && (t > best.t || (t == best.t && !closerTie(tri, *bestTri)))) return false;
    best = RayHit{t, tri.instance, tri.triangle};
    bestTri = &tri;
    tMax = t;
    return false;
  });
  return best;
}

bool TriangleBvh::anyHit(const glm::dvec3& origin, const glm::dvec3& direction, double tMin, double tMax) const {
  bool hit = false;
  traverse(origin, direction, tMin, tMax, [&](const BvhTriangle& tri) {
    double t = 0.0;
    hit = intersectTriangle(tri, origin, direction, tMin, tMax, t);
    return hit;
  });
  return hit;
}

}  // namespace shadowref::oracle
