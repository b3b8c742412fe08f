// Projection and view matrices, in double precision, laid out as OpenGL's (column-major, the
// camera looks down -z, clip space -w <= x, y, z <= w).
#pragma once

#include <glm/glm.hpp>

namespace shadowref {

// glFrustum.
glm::dmat4 frustum(double left, double right, double bottom, double top, double nearVal, double farVal);
// gluPerspective, fovY in degrees.
glm::dmat4 perspective(double fovYDegrees, double aspect, double nearVal, double farVal);
// glOrtho.
glm::dmat4 ortho(double left, double right, double bottom, double top, double nearVal, double farVal);

// The infinite projection P_inf ([Kuhn 2016, §3.3], after [Blinn 1993]): the frustum matrix in the
// limit far -> infinity, third row (0, 0, -1, -2 near). A point at infinity (w = 0) lands exactly
// on the far plane (depth 1). With epsilon > 0 the third row becomes (0, 0, epsilon - 1,
// (epsilon - 2) near), which keeps such points a little inside the far plane where float
// rounding would otherwise push them beyond it.
glm::dmat4 infiniteFrustum(double left, double right, double bottom, double top, double nearVal,
                           double epsilon = 0.0);
glm::dmat4 infinitePerspective(double fovYDegrees, double aspect, double nearVal, double epsilon = 0.0);

// gluLookAt.
glm::dmat4 lookAt(const glm::dvec3& eye, const glm::dvec3& target, const glm::dvec3& up);

}  // namespace shadowref
