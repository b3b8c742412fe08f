// A bounding volume hierarchy over world-space triangles, in double precision, for the oracle's
// primary rays (first hit) and shadow rays (any hit). Median split on the longest axis of the
// centroids; deterministic (stable sort, no hashing).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scene/mesh.h"

namespace shadowref::oracle {

struct BvhTriangle {
  glm::dvec3 a{0.0}, b{0.0}, c{0.0};
  int instance = -1;
  uint32_t triangle = 0;  // index into the instance mesh's triangles
  // firstHit passes through the triangle from behind (its normal, (b - a) x (c - a), pointing
  // along the ray), as the scene pass culls back faces; anyHit never does.
  bool backCulled = false;
};

struct RayHit {
  double t = 0.0;
  int instance = -1;  // -1: no hit
  uint32_t triangle = 0;
  bool found() const { return instance >= 0; }
};

// Möller-Trumbore in double. The barycentric bounds are widened by 1e-10 so that a ray through an
// edge shared by two triangles cannot slip between them by rounding (the nearer one wins anyway).
bool intersectTriangle(const BvhTriangle& tri, const glm::dvec3& origin, const glm::dvec3& direction,
                       double tMin, double tMax, double& t);

class TriangleBvh {
 public:
  TriangleBvh() = default;
  explicit TriangleBvh(std::vector<BvhTriangle> triangles);

  // The nearest hit with t in [tMin, tMax], not counting the back of a backCulled triangle; ties
  // go to the lower (instance, triangle).
  RayHit firstHit(const glm::dvec3& origin, const glm::dvec3& direction, double tMin, double tMax) const;
  bool anyHit(const glm::dvec3& origin, const glm::dvec3& direction, double tMin, double tMax) const;

  const std::vector<BvhTriangle>& triangles() const { return triangles_; }
  size_t nodeCount() const { return nodes_.size(); }

 private:
  struct Node {
    Aabb bounds;
    uint32_t first = 0, count = 0;  // leaf: triangles [first, first+count)
    uint32_t left = 0, right = 0;   // inner node: children
  };
  uint32_t build(uint32_t first, uint32_t count);
  // Calls visit(triangle) for the triangles of every leaf whose box the ray meets within
  // [tMin, tMax], reading tMax afresh at each box; stops when visit returns true.
  template <class Visit>
  void traverse(const glm::dvec3& origin, const glm::dvec3& direction, double tMin, const double& tMax,
                Visit&& visit) const;

  std::vector<BvhTriangle> triangles_;
  std::vector<Node> nodes_;
};

}  // namespace shadowref::oracle
