// The camera as the oracle sees it: primary rays through pixel centres and the projection of
// homogeneous world points to the screen, with clipping in homogeneous clip space.
//
// Rays come from the inverse of projection · view applied to the NDC of the pixel centre, not from
// the rasterizer's code: the window position (x + 0.5, y + 0.5), row 0 at the bottom, is mapped
// back through the viewport to NDC, then to the world point on the near plane (NDC z = -1).
// The ray is eye + t d with d = nearPoint - eye, so t = 1 on the near plane: what the rasterizer
// clips away lies at t < 1. With a finite far plane, tFar is where the ray leaves the frustum.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "shadow/scene_view.h"

namespace shadowref::oracle {

struct PixelRay {
  glm::dvec3 origin{0.0};     // the eye
  glm::dvec3 direction{0.0};  // eye -> near-plane point of the pixel centre
  double tNear = 1.0;
  double tFar = 0.0;          // infinity for P_inf
};

struct CameraModel {
  glm::dmat4 viewProjection{1.0};
  glm::dmat4 inverseViewProjection{1.0};
  Viewport viewport;
  glm::dvec3 eye{0.0};
  bool infinite = true;

  PixelRay rayThrough(double windowX, double windowY) const;
  PixelRay pixelRay(int x, int y) const { return rayThrough(x + 0.5, y + 0.5); }
  // Clip coordinates of a homogeneous world point (w = 0 allowed).
  glm::dvec4 toClip(const glm::dvec4& world) const { return viewProjection * world; }
  // Window x, y of a clip point with w > 0.
  glm::dvec2 toWindow(const glm::dvec4& clip) const;
};

CameraModel makeCameraModel(const SceneView& view);

// Sutherland-Hodgman in homogeneous clip space against the near plane (z >= -w) and a guard band
// |x|, |y| <= kGuardBand · w. Points at infinity (w = 0 in world space) are ordinary points here.
// What survives has w > 0 and projects to finite window coordinates; what is cut off cannot be met
// by a pixel ray beyond the near plane (the guard band is wider than the screen), so the parts of an
// edge or a polygon inside the screen are unchanged.
inline constexpr double kGuardBand = 2.0;
std::vector<glm::dvec4> clipPolygonToView(std::vector<glm::dvec4> polygon);
// Returns false when nothing is left.
bool clipSegmentToView(glm::dvec4& a, glm::dvec4& b);

}  // namespace shadowref::oracle
