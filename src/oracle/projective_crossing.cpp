#include "oracle/projective_crossing.h"

#include <cmath>
#include <limits>

namespace shadowref::oracle {

namespace {

bool lexicographicLess(const glm::dvec4& a, const glm::dvec4& b) {
  for (int i = 0; i < 4; ++i) {
    if (a[i] != b[i]) return a[i] < b[i];
  }
  return false;
}

double det3(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  return glm::dot(glm::cross(a, b), c);
}

// The vertices' coordinates without row k, as three 3-vectors (one per vertex).
std::array<glm::dvec3, 3> dropRow(const std::array<glm::dvec4, 3>& v, int k) {
  std::array<glm::dvec3, 3> out{};
  for (int j = 0; j < 3; ++j) {
    int r = 0;
    for (int i = 0; i < 4; ++i) {
      if (i != k) out[j][r++] = v[j][i];
    }
  }
  return out;
}

// The edge test's sign with the tie rule of the header: zero is positive in canonical order.
double edgeSign(const ProjectiveTriangle& t, int i, const Plucker& line) {
  const double canonical = pluckerPairing(t.edge[i], line);
  return (canonical >= 0.0 ? 1.0 : -1.0) * t.edgeFlip[i];
}

}  // namespace

Plucker pluckerLine(const glm::dvec4& a, const glm::dvec4& b) {
  return {a[0] * b[1] - a[1] * b[0], a[0] * b[2] - a[2] * b[0], a[0] * b[3] - a[3] * b[0],
          a[1] * b[2] - a[2] * b[1], a[1] * b[3] - a[3] * b[1], a[2] * b[3] - a[3] * b[2]};
}

double pluckerPairing(const Plucker& ab, const Plucker& xy) {
  // det[A B X Y] = Σ over row pairs {i<j} of (-1)^(i+j+1) L_ij(AB) L_kl(XY), {k,l} the other rows.
  return ab[0] * xy[5] - ab[1] * xy[4] + ab[2] * xy[3] + ab[3] * xy[2] - ab[4] * xy[1] + ab[5] * xy[0];
}

ProjectiveTriangle makeProjectiveTriangle(const glm::dvec4& v0, const glm::dvec4& v1, const glm::dvec4& v2) {
  ProjectiveTriangle t;
  t.v = {v0, v1, v2};
  // Cofactor expansion of det[V0 V1 V2 X] along the column X: X_k (-1)^(k+3) det(rows != k). A
  // triangle at infinity (all w = 0) gets plane (0, 0, 0, c) exactly: every other minor has a zero row.
  for (int k = 0; k < 4; ++k) {
    const std::array<glm::dvec3, 3> m = dropRow(t.v, k);
    const double sign = (k % 2 == 1) ? 1.0 : -1.0;  // (-1)^(k+3)
    t.plane[k] = sign * det3(m[0], m[1], m[2]);
  }
  for (int i = 0; i < 3; ++i) {
    const glm::dvec4& a = t.v[i];
    const glm::dvec4& b = t.v[(i + 1) % 3];
    const bool canonical = !lexicographicLess(b, a);
    t.edge[i] = canonical ? pluckerLine(a, b) : pluckerLine(b, a);
    t.edgeFlip[i] = canonical ? 1.0 : -1.0;
  }
  return t;
}

ProjectiveSegment makeSegment(const glm::dvec4& p, const glm::dvec4& q) {
  return ProjectiveSegment{p, q, pluckerLine(p, q)};
}

ProjectiveSegment makeRayToInfinity(const glm::dvec3& origin, const glm::dvec3& direction, double tStart) {
  return makeSegment(glm::dvec4(origin + tStart * direction, 1.0), glm::dvec4(direction, 0.0));
}

Crossing crossSegment(const ProjectiveTriangle& t, const ProjectiveSegment& s) {
  Crossing c;
  const double piP = glm::dot(t.plane, s.p);
  const double piQ = glm::dot(t.plane, s.q);
  if (piP == 0.0) return c;                        // starts on the plane: no transversal crossing
  if (piQ != 0.0 && (piP > 0.0) == (piQ > 0.0)) return c;  // both ends on one side
  // c0, c1, c2 — the side products det[Va Vb P Q] of the three edges a -> b — must all have the
  // sign opposite to c4 = π(P).
  const double want = piP > 0.0 ? -1.0 : 1.0;
  for (int edge = 0; edge < 3; ++edge) {
    if (edgeSign(t, edge, s.line) != want) return c;
  }
  c.hit = true;
  c.entering = piP < 0.0;
  c.mu = std::abs(piQ);
  c.nu = std::abs(piP);
  return c;
}

double rayParameter(const Crossing& c, double tStart) {
  if (c.mu == 0.0) return std::numeric_limits<double>::infinity();
  return tStart + c.nu / c.mu;
}

}  // namespace shadowref::oracle
