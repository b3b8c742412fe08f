// The pixels near a primitive edge of a conformance scenario, where GL leaves the implementation
// freedom (fill-rule ties, rounding of clipped vertices): the product's classification
// (src/trace/edge_mask.h), which `shadowref replay` applies to captured frames.
#pragma once

#include <vector>

#include "osmesa/scenario.h"

namespace shadowref::conformance {

// One flag per pixel (bottom row first): true when the pixel centre lies within `distance`
// pixels of an edge of any triangle drawn in the scenario.
std::vector<bool> edgeMask(const Scenario& scenario, double distance = 1.0);

}  // namespace shadowref::conformance
