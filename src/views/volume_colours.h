// The colours of the volume view (--view volumes): front and back faces of each light's volumes
// ([SV slides] draws them red and blue) in hues of their own, chosen away from the scene's
// material hues, so that no face vanishes on a surface of its own colour (blue back faces on the
// room's blue chairs) and each light's volumes are told apart.
#pragma once

#include <array>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace shadowref::views {

// The hue of a colour in degrees [0, 360) and its saturation (HSV, [Smith 1978]); a grey has
// saturation 0 and hue 0.
double hueDegrees(const glm::dvec3& rgb);
double saturation(const glm::dvec3& rgb);

// The distance of two hues around the circle, 0..180 degrees.
double hueDistance(double a, double b);

// Materials whose diffuse colour has a saturation below this have no hue to clash with.
inline constexpr double kHuedSaturation = 0.2;

// 2 · lights hues, each chosen in turn (front of light 0, back of light 0, front of light 1, ...)
// on a 1-degree grid as the one farthest around the circle from the hues of the coloured
// materials (saturation ≥ kHuedSaturation) and from those chosen before; ties go to the smaller
// hue. With no coloured material the first is 0 (red). Each as a fully saturated colour (HSV s = 1,
// v = 1): [light][0] the front faces, [light][1] the back faces.
std::vector<std::array<glm::dvec3, 2>> volumeColours(std::span<const glm::dvec3> materialColours, size_t lights);

// The diffuse colours of the scene's materials and volumeColours for its lights.
std::vector<std::array<glm::dvec3, 2>> volumeColours(const Scene& scene);

}  // namespace shadowref::views
