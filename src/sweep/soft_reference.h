// Ground truth for soft shadows: the fraction of an area light each pixel's surface point sees,
// by shadow rays to many points spread evenly over the light (a high-sample
// reference). The surface points are the oracle's primary hits, so the reference and the hard
// oracle agree on what every pixel shows.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"
#include "oracle/oracle.h"
#include "sweep/shadow_error.h"

namespace shadowref::sweep {

// `samples` points on the light: AreaSquare, a square grid of cell centres over [-s, s]^2 in the
// horizontal plane through the light (square_y's lights span it); AreaSphere, a Fibonacci spiral
// on the sphere of radius s (sphere14's lights lie on it). Deterministic: no random numbers.
std::vector<glm::dvec3> areaLightSamples(Reference shape, const glm::dvec3& centre, double s, int samples);

// Per pixel (the oracle's layout), the fraction of samples a shadow ray from the hit reaches;
// 0 where the pixel has no hit. Casters are the instances casting for `light` (range and
// cast_shadows, their shadow proxies), as for the oracle's own `lit`.
std::vector<float> areaLightVisibility(const Scene& scene, const Light& light, const std::vector<glm::dvec3>& samples,
                                       const oracle::OracleImage& primary, int threads);

}  // namespace shadowref::sweep
