// The light's view and projection for a shadow map ([Hempe 2004, §3.1, §5.1]), and the texture
// matrix T = bias · P_light · V_light that carries a world position into the map's [0, 1] texture
// space.
//
// Which world region a map covers is the caller's choice: the functions fit to the box they are
// given. The frame passes give the scene's bounding box (every caster and receiver), not the
// camera frustum ∩ scene box: a caster outside the view frustum can still shadow a visible
// receiver, and trapezoidal shadow maps (trapezoid.h) refocus the map on the frustum afterwards
// with N_T, keeping the light's depth range over the whole scene.
#pragma once

#include <array>

#include <glm/glm.hpp>

#include "scene/mesh.h"
#include "scene/scene.h"

namespace shadowref {

// The matrices of one depth-map render from the light: world -> light eye -> light clip.
struct LightView {
  glm::dmat4 view{1.0};        // V_light (gluLookAt)
  glm::dmat4 projection{1.0};  // P_light (glOrtho or gluPerspective)
  double nearPlane = 0.0, farPlane = 1.0;
};

// The fitted depth range is widened by this fraction of its extent at each end, so the box's
// nearest and farthest corners are not clipped by rounding on the map's near and far planes.
inline constexpr double kLightDepthMargin = 1e-3;

// The up vector the light views use: world +y, or world −z when the light points (almost) along y
// (|d.y| > 0.999), where +y would be nearly parallel to the view direction.
glm::dvec3 lightUpVector(const glm::dvec3& direction);

// Directional light ([Hempe 2004, §5.1.2]: "orthografische Sicht"): looks along Light::direction
// from outside `bounds`, with glOrtho fitted tightly to the box's eight corners in light eye space
// (x, y exactly; depth with kLightDepthMargin).
LightView directionalLightView(const Light& light, const Aabb& bounds);

// Spot light: gluPerspective from the light's position along its axis with fovY = 2 · cutoff and
// aspect 1, so the map's square covers the spot cone's circle. Near and far fitted to `bounds`:
// far = the farthest box corner along the axis, near = the nearest one in front of the light, but
// at least far · kMinNearOverFar (the light may stand inside the box; a tiny near plane would
// spend the depth range's precision right at the light).
inline constexpr double kMinNearOverFar = 1e-3;
LightView spotLightView(const Light& light, const Aabb& bounds);

// The map's view for a directional or spot light (the two [Hempe 2004, §3.2] allows):
// directionalLightView or spotLightView. Point lights need the six views of pointLightCubeViews
// instead.
LightView shadowLightView(const Light& light, const Aabb& bounds);

// The bias matrix of [Hempe 2004, §3.1 / Listing 4]: x, y, z from [−1, 1] to [0, 1]. The thesis
// prints it with the translation 0.5, 0.5, 0.5 in the last ROW: that is OpenGL's column-major array
// order (the MATRIX4X4 constructor of Listing 4 takes the array), not the mathematical matrix,
// whose translation is in the last column. Here: the mathematical matrix, for column vectors.
glm::dmat4 biasMatrix();

// T = bias · P_light · V_light ([Hempe 2004, §3.1 and Listing 4]), applied to WORLD positions. The
// thesis' formula T = P_l · V_l · V_c⁻¹ includes the inverse camera matrix because EYE_LINEAR
// texgen produces eye coordinates; a fragment shader here gets the world position directly.
glm::dmat4 textureMatrix(const LightView& light);
// With the trapezoidal warp ([Hempe 2004, Listing 11]): T = bias · N_T · P_light · V_light.
glm::dmat4 textureMatrix(const LightView& light, const glm::dmat4& trapezoidNT);

// Point lights, beyond the documents ([Hempe 2004, §3.2] says shadow maps cannot do omnidirectional
// lights): six perspective maps, fovY 90°, aspect 1, one per cube face, oriented as OpenGL's cube
// map faces ([GL 2.1, §3.8.6], the major-axis table): face f's map, looked up with
// textureMatrix(views[f]), is the face image GL would sample for a direction whose major axis
// selects f.
enum class CubeFace : int { PositiveX = 0, NegativeX, PositiveY, NegativeY, PositiveZ, NegativeZ };

// GL's major-axis rule: the component of largest magnitude picks the face, its sign the
// direction. Ties (GL leaves them open) go to x before y before z; the zero vector gives +x.
CubeFace cubeFaceFor(const glm::dvec3& direction);

// The face's view direction and up vector (target = position + forward).
glm::dvec3 cubeFaceForward(CubeFace face);
glm::dvec3 cubeFaceUp(CubeFace face);

// Far = the distance from the light to the farthest corner of `bounds`; near = far ·
// kMinNearOverFar unless `nearPlane` > 0 is given.
std::array<LightView, 6> pointLightCubeViews(const Light& light, const Aabb& bounds, double nearPlane = 0.0);

}  // namespace shadowref
