#include "gl/projection.h"

#include <cmath>
#include <numbers>

namespace shadowref {

namespace {
double halfHeightAtNear(double fovYDegrees, double nearVal) {
  return nearVal * std::tan(fovYDegrees * std::numbers::pi / 360.0);
}
}  // namespace

glm::dmat4 frustum(double l, double r, double b, double t, double n, double f) {
  glm::dmat4 m(0.0);  // m[column][row]
  m[0][0] = 2.0 * n / (r - l);
  m[1][1] = 2.0 * n / (t - b);
  m[2][0] = (r + l) / (r - l);
  m[2][1] = (t + b) / (t - b);
  m[2][2] = -(f + n) / (f - n);
  m[2][3] = -1.0;
  m[3][2] = -2.0 * f * n / (f - n);
  return m;
}

glm::dmat4 perspective(double fovYDegrees, double aspect, double n, double f) {
  const double t = halfHeightAtNear(fovYDegrees, n);
  return frustum(-t * aspect, t * aspect, -t, t, n, f);
}

glm::dmat4 ortho(double l, double r, double b, double t, double n, double f) {
  glm::dmat4 m(1.0);
  m[0][0] = 2.0 / (r - l);
  m[1][1] = 2.0 / (t - b);
  m[2][2] = -2.0 / (f - n);
  m[3][0] = -(r + l) / (r - l);
  m[3][1] = -(t + b) / (t - b);
  m[3][2] = -(f + n) / (f - n);
  return m;
}

glm::dmat4 infiniteFrustum(double l, double r, double b, double t, double n, double epsilon) {
  glm::dmat4 m(0.0);
  m[0][0] = 2.0 * n / (r - l);
  m[1][1] = 2.0 * n / (t - b);
  m[2][0] = (r + l) / (r - l);
  m[2][1] = (t + b) / (t - b);
  m[2][2] = epsilon - 1.0;
  m[2][3] = -1.0;
  m[3][2] = (epsilon - 2.0) * n;
  return m;
}

glm::dmat4 infinitePerspective(double fovYDegrees, double aspect, double n, double epsilon) {
  const double t = halfHeightAtNear(fovYDegrees, n);
  return infiniteFrustum(-t * aspect, t * aspect, -t, t, n, epsilon);
}

glm::dmat4 lookAt(const glm::dvec3& eye, const glm::dvec3& target, const glm::dvec3& up) {
  const glm::dvec3 f = glm::normalize(target - eye);
  const glm::dvec3 s = glm::normalize(glm::cross(f, up));
  const glm::dvec3 u = glm::cross(s, f);
  glm::dmat4 m(1.0);
  m[0][0] = s.x; m[1][0] = s.y; m[2][0] = s.z;
  m[0][1] = u.x; m[1][1] = u.y; m[2][1] = u.z;
  m[0][2] = -f.x; m[1][2] = -f.y; m[2][2] = -f.z;
  m[3][0] = -glm::dot(s, eye);
  m[3][1] = -glm::dot(u, eye);
  m[3][2] = glm::dot(f, eye);
  return m;
}

}  // namespace shadowref
