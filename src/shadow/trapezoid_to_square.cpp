#include "shadow/trapezoid_to_square.h"

#include <cmath>

namespace shadowref {

namespace {

// The matrices below are written row by row as [Hempe 2004, §4.1.2] prints them (for column
// vectors); glm stores columns, hence the transpose.
glm::dmat4 fromRows(const glm::dvec4& r0, const glm::dvec4& r1, const glm::dvec4& r2, const glm::dvec4& r3) {
  return glm::transpose(glm::dmat4(r0, r1, r2, r3));
}

glm::dvec4 point(const glm::dvec2& p) { return {p.x, p.y, 0.0, 1.0}; }

glm::dmat4 translationXY(const glm::dvec4& u) {
  return fromRows({1.0, 0.0, 0.0, -u.x}, {0.0, 1.0, 0.0, -u.y}, {0.0, 0.0, 1.0, 0.0}, {0.0, 0.0, 0.0, 1.0});
}

double cross2(const glm::dvec2& a, const glm::dvec2& b) { return a.x * b.y - a.y * b.x; }

}  // namespace

glm::dmat4 trapezoidStepT1(const TrapezoidCorners& t) {
  const glm::dvec2 u = (t[2] + t[3]) / 2.0;
  return translationXY(point(u));
}

glm::dmat4 trapezoidStepR(const TrapezoidCorners& t) {
  const glm::dvec2 u = (t[2] - t[3]) / glm::length(t[2] - t[3]);
  return fromRows({u.x, u.y, 0.0, 0.0}, {u.y, -u.x, 0.0, 0.0}, {0.0, 0.0, 1.0, 0.0}, {0.0, 0.0, 0.0, 1.0});
}

glm::dmat4 trapezoidStepT2(const TrapezoidCorners& t, const glm::dmat4& soFar) {
  const glm::dvec4 u = soFar * point(sideLineIntersection(t));
  return translationXY(u);
}

glm::dmat4 trapezoidStepH(const TrapezoidCorners& t, const glm::dmat4& soFar) {
  const glm::dvec4 u = soFar * (point(t[2]) + point(t[3])) / 2.0;
  return fromRows({1.0, -u.x / u.y, 0.0, 0.0}, {0.0, 1.0, 0.0, 0.0}, {0.0, 0.0, 1.0, 0.0}, {0.0, 0.0, 0.0, 1.0});
}

glm::dmat4 trapezoidStepS1(const TrapezoidCorners& t, const glm::dmat4& soFar) {
  const glm::dvec4 u = soFar * point(t[2]);
  return fromRows({1.0 / u.x, 0.0, 0.0, 0.0}, {0.0, 1.0 / u.y, 0.0, 0.0}, {0.0, 0.0, 1.0, 0.0},
                  {0.0, 0.0, 0.0, 1.0});
}

glm::dmat4 trapezoidStepN() {
  return fromRows({1.0, 0.0, 0.0, 0.0}, {0.0, 1.0, 0.0, 1.0}, {0.0, 0.0, 1.0, 0.0}, {0.0, 1.0, 0.0, 0.0});
}

glm::dmat4 trapezoidStepT3(const TrapezoidCorners& t, const glm::dmat4& soFar) {
  const glm::dvec4 u = soFar * point(t[0]);
  const glm::dvec4 v = soFar * point(t[2]);
  const double centre = (u.y / u.w + v.y / v.w) / 2.0;
  return fromRows({1.0, 0.0, 0.0, 0.0}, {0.0, 1.0, 0.0, -centre}, {0.0, 0.0, 1.0, 0.0}, {0.0, 0.0, 0.0, 1.0});
}

glm::dmat4 trapezoidStepS2(const TrapezoidCorners& t, const glm::dmat4& soFar) {
  const glm::dvec4 u = soFar * point(t[0]);
  return fromRows({1.0, 0.0, 0.0, 0.0}, {0.0, -u.w / u.y, 0.0, 0.0}, {0.0, 0.0, 1.0, 0.0},
                  {0.0, 0.0, 0.0, 1.0});
}

glm::dvec2 sideLineIntersection(const TrapezoidCorners& t) {
  // Line a: t0 + α (t3 − t0); line b: t1 + β (t2 − t1).
  const glm::dvec2 da = t[3] - t[0], db = t[2] - t[1];
  const double alpha = cross2(t[1] - t[0], db) / cross2(da, db);
  return t[0] + alpha * da;
}

glm::dmat4 trapezoidToSquare(const TrapezoidCorners& t) {
  const glm::dmat4 T1 = trapezoidStepT1(t);
  const glm::dmat4 R = trapezoidStepR(t);
  const glm::dmat4 T2 = trapezoidStepT2(t, R * T1);
  const glm::dmat4 H = trapezoidStepH(t, T2 * R * T1);
  const glm::dmat4 S1 = trapezoidStepS1(t, H * T2 * R * T1);
  const glm::dmat4 N = trapezoidStepN();
  const glm::dmat4 T3 = trapezoidStepT3(t, N * S1 * H * T2 * R * T1);
  const glm::dmat4 S2 = trapezoidStepS2(t, T3 * N * S1 * H * T2 * R * T1);
  return S2 * T3 * N * S1 * H * T2 * R * T1;
}

glm::dmat4 parallelogramToSquare(const TrapezoidCorners& t) {
  // A = [e1 e2] maps (1, 0) to e1 = (t1 − t0)/2 and (0, 1) to e2 = (t3 − t0)/2, and the centre
  // c = (t1 + t3)/2 is the image of the origin; N_T is the inverse of p = c + A·x.
  const glm::dvec2 e1 = (t[1] - t[0]) / 2.0, e2 = (t[3] - t[0]) / 2.0, c = (t[1] + t[3]) / 2.0;
  glm::dmat4 forward(1.0);
  forward[0] = glm::dvec4(e1, 0.0, 0.0);
  forward[1] = glm::dvec4(e2, 0.0, 0.0);
  forward[3] = glm::dvec4(c, 0.0, 1.0);
  return glm::inverse(forward);
}

}  // namespace shadowref
