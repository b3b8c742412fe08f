// The pixels near a primitive edge, where GL leaves the implementation freedom: which of two
// triangles owns a pixel centre exactly on (or within rounding of) their shared edge, and how
// clipped vertices are rounded. Differences there are explained by the fill rule, not by the
// per-fragment operations the comparison is after (docs/conformance.md).
#pragma once

#include <vector>

#include "osmesa/scenario.h"

namespace shadowref::conformance {

// One flag per pixel (bottom row first): true when the pixel centre lies within `distance`
// pixels of an edge of any triangle drawn in the scenario, after clipping it in double precision
// against the near and far planes (unless depth clamp) and projecting it with its viewport.
std::vector<bool> edgeMask(const Scenario& scenario, double distance = 1.0);

}  // namespace shadowref::conformance
