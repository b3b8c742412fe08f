// McGuire's choice between z-pass and z-fail per object ([Kuhn 2016, §3.2, §4.2.1, §4.3.2];
// [McGuire et al. 2003]).
//
// Z-pass counts wrongly exactly where a shadow volume is cut by the near plane inside the view,
// i.e. where some point p of the near-plane rectangle lies in the shadow of (or inside) an
// occluder: the segment from p to the light hits the occluder. The union of those segments is the
// "occlusion pyramid": the convex hull of the light and the four near-plane corners. For a
// directional light the segments become rays towards the light and the pyramid a semi-infinite
// prism. An occluder needs z-fail iff it meets that hull; its bounding box meeting the hull is a
// conservative test (it may say z-fail when z-pass would do, never the reverse). The camera inside
// a shadow volume is the extreme case: the whole near rectangle is in shadow.
//
// The hull-versus-box test is a separating-axis test (both are convex): box axes, hull face
// normals, and cross products of box axes with hull edges. Axes that degenerate are skipped and
// touching counts as meeting, both on the conservative side.
#pragma once

#include <array>

#include <glm/glm.hpp>

#include "scene/mesh.h"
#include "scene/scene.h"

namespace shadowref {

struct OcclusionPyramid {
  // World space, counter-clockwise seen from the camera: lower left, lower right, upper right,
  // upper left.
  std::array<glm::dvec3, 4> nearCorners;
  // Apex: (position, 1) for a point or spot light; (direction towards the light, 0) for a
  // directional light, which makes the pyramid a prism open towards the light.
  glm::dvec4 light{0.0, 0.0, 0.0, 1.0};
};

// The near-plane rectangle of [Kuhn 2016, §4.2.1], with the camera basis of gluLookAt
// (projection.h). Erratum: [Kuhn 2016, §4.2.1] writes fovX = 2·atan(fovY·0.5)·aspect and then
// halfWidth = tan(fovX/2)·near; that is neither the horizontal field of view nor the frustum's
// width. The frustum built by perspective()/infinitePerspective() has halfHeight = tan(fovY/2)·near
// and halfWidth = tan(fovY/2)·aspect·near, which is what is used here.
std::array<glm::dvec3, 4> nearPlaneCorners(const Camera& camera, double aspect);

OcclusionPyramid makeOcclusionPyramid(const Camera& camera, double aspect, const glm::dvec4& worldLight);

// True when `worldBox` meets the pyramid (conservatively). An empty box meets nothing.
bool intersects(const OcclusionPyramid& pyramid, const Aabb& worldBox);

// [Kuhn 2016, §4.3.2]: does an occluder with this world bounding box need z-fail?
bool needsZFail(const Aabb& worldBox, const Camera& camera, double aspect, const glm::dvec4& worldLight);

}  // namespace shadowref
