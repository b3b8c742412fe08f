// How far a rendered shadow is from the truth. The renderer's visibility of each light per pixel
// is read from the frame (stencil counts for shadow volumes, colour for shadow maps) and compared
// with the oracle's shadow ray (hard) or an area-light reference (soft).
#pragma once

#include <string_view>
#include <vector>

#include "scene/scene.h"

namespace shadowref::sweep {

// What the renderer's shadow is compared with.
enum class Reference {
  HardLight,   // the light as a point: the oracle's shadow ray per pixel (src/oracle)
  AreaSquare,  // the square [-s, s]^2 around the light in its horizontal plane (square_y's span)
  AreaSphere,  // the sphere of radius s around the light (sphere14's points lie on it)
};
// "point", "square", "sphere": the names a sweep file writes.
const char* name(Reference reference);

struct ShadowError {
  long pixels = 0;         // (pixel, light) pairs compared
  double mae = 0.0;        // mean |renderer visibility - reference visibility|
  double wrong = 0.0;      // fraction where the two disagree on "lit" (visibility >= 0.5)
  double wrongCore = 0.0;  // the same, leaving out the oracle's near-edge pixels
  double shadowed = 0.0;   // fraction the reference calls shadowed (< 0.5): what "none" gets wrong
};

struct ErrorSettings {
  Reference reference = Reference::HardLight;
  double softSpacing = 0.0;
  int referenceSamples = 256;
  int threads = 0;  // oracle and reference; 0: all cores
  bool forceInfiniteOracle = false;
};

// Which pixels count: the oracle sees a surface there, and light i visibly adds to it (the
// unshadowed frame with light i alone is brighter than the ambient-only frame by more than
// kContributionThreshold in mean RGB). Elsewhere a shadow, right or wrong, cannot be seen.
inline constexpr float kContributionThreshold = 0.02f;

ShadowError measureShadowError(const Scene& scene, std::string_view method, const ErrorSettings& settings);

}  // namespace shadowref::sweep
