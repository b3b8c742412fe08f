// Exact-in-form crossing of a segment with a triangle in oriented projective 3-space: the test
// the oracle counts shadow-volume polygons with, independent of the rasterizer.
//
// Shadow volumes have vertices at infinity (w = 0, [Kuhn 2016, §3.4]): a side quad (A, B, D∞, C∞)
// is the part of the plane through A, B and the light between the rays from the light through A and
// B; a back cap lies in the plane at infinity. Such a "triangle" is the set of positive
// combinations
//   X = λ0 V0 + λ1 V1 + λ2 V2,  λi >= 0
// of its homogeneous vertices (every vertex has w >= 0). A segment from P to Q (homogeneous, w >= 0;
// Q = (d, 0) is the end at infinity of the ray o + t d) is the set μ P + ν Q, μ, ν >= 0. Oriented
// projective geometry (Stolfi), not plain projective: (d, 0) and (-d, 0) are different points, as
// they are for the rasterizer, which keeps only w_clip > 0 after clipping.
//
// Five vectors in R^4 have (generically) a one-dimensional kernel, and Cramer's rule gives it:
//   c0 V0 + c1 V1 + c2 V2 + c3 P + c4 Q = 0 with
//   c0 = det[V1 V2 P Q], c1 = det[V2 V0 P Q], c2 = det[V0 V1 P Q],
//   c3 = -det[V0 V1 V2 Q] = -π(Q),  c4 = det[V0 V1 V2 P] = π(P).
// The segment meets the triangle iff c0, c1, c2 share one sign s and c3, c4 the other: the plane
// functional π has opposite signs at P and Q (the segment crosses the plane) and the three edge
// tests — Plücker side products of the line PQ with each edge — agree. The meeting point is
// |π(Q)| P + |π(P)| Q. π(Q) = 0 exactly (a back cap and the ray's end at infinity) is a crossing at
// the very end, and counts: the segment is closed there, as the rasterizer keeps back caps at
// depth 1 (P_inf, [Kuhn 2016, §3.3]).
//
// Orientation: for finite vertices π(X) = -n·(x - v0) with n = (v1 - v0) × (v2 - v0), so the side
// a counter-clockwise-from-outside triangle faces (its outside) is π < 0. A ray ENTERS the volume
// through a face when its start P is on that outside.
//
// Ties (the line exactly through an edge) are broken by simulation of simplicity on one level: each
// edge's side product is computed from its two vertices in a canonical (lexicographic) order, so the
// two triangles sharing the edge see exactly opposite values, and a zero counts as positive in the
// canonical direction. A line through a shared edge is then claimed by exactly one of the two
// triangles, as watertight rasterization claims a pixel on a shared edge once.
#pragma once

#include <array>

#include <glm/glm.hpp>

namespace shadowref::oracle {

// The six Plücker coordinates L_ij = A_i B_j - A_j B_i (ij = 01, 02, 03, 12, 13, 23) of the line
// through homogeneous points A and B.
using Plucker = std::array<double, 6>;
Plucker pluckerLine(const glm::dvec4& a, const glm::dvec4& b);
// det[A B X Y] from the Plücker coordinates of lines AB and XY (Laplace expansion on two columns).
double pluckerPairing(const Plucker& ab, const Plucker& xy);

// A triangle prepared for many segment tests.
struct ProjectiveTriangle {
  std::array<glm::dvec4, 3> v{};
  glm::dvec4 plane{0.0};                 // π(X) = dot(plane, X) = det[V0 V1 V2 X]
  std::array<Plucker, 3> edge{};         // edge i runs v[i] -> v[i+1], stored in canonical order
  std::array<double, 3> edgeFlip{};      // +1 when v[i] -> v[i+1] is the canonical order, else -1
};

ProjectiveTriangle makeProjectiveTriangle(const glm::dvec4& v0, const glm::dvec4& v1, const glm::dvec4& v2);

// A segment from p to q (homogeneous, w >= 0), prepared for many triangle tests.
struct ProjectiveSegment {
  glm::dvec4 p{0.0}, q{0.0};
  Plucker line{};
};
ProjectiveSegment makeSegment(const glm::dvec4& p, const glm::dvec4& q);
// The ray o + t d for t >= tStart, to its end at infinity (d, 0).
ProjectiveSegment makeRayToInfinity(const glm::dvec3& origin, const glm::dvec3& direction, double tStart);

struct Crossing {
  bool hit = false;
  bool entering = false;  // P lies on the triangle's outside (π(P) < 0): the segment enters
  double mu = 0.0, nu = 0.0;  // the crossing point is mu P + nu Q (mu, nu >= 0)
};

Crossing crossSegment(const ProjectiveTriangle& triangle, const ProjectiveSegment& segment);

// For a segment from makeRayToInfinity: the ray parameter t of a crossing (infinity at the end).
double rayParameter(const Crossing& c, double tStart);

}  // namespace shadowref::oracle
