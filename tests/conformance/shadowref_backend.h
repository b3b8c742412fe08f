// Renders a conformance scenario with shadowref's raster pipeline in its 24-bit depth mode.
#pragma once

#include "osmesa/scenario.h"

namespace shadowref::conformance {

Readback renderWithShadowref(const Scenario& scenario);

}  // namespace shadowref::conformance
