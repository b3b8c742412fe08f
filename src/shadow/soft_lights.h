// Soft shadows by extra lights ([Kuhn 2016, §3.6]; [Hempe 2004, §4.2]): a light becomes itself plus
// lights around it, each carrying colour / count, and every shadow pass is repeated per light.
#pragma once

#include <vector>

#include "scene/scene.h"

namespace shadowref {

// SoftShape::None -> the light itself. SquareX/Y/Z -> the light plus 8 on the square of side
// 2·spacing centred on it, all sharing the light's X, Y or Z coordinate
// ([Kuhn 2016, §4.2, Fig. 4.2]: "eine Fläche bei der alle Lichtquellen die Z-Koordinate teilen");
// Sphere14 -> the light plus 6 axis and 8 diagonal points at distance `spacing`
// ([Kuhn 2016, §3.6]); AreaEdge16 -> 16 lights evenly spaced on the edge of a square area light of
// side `spacing` in the plane orthogonal to the light's direction ([Hempe 2004, §4.2]: the original
// light is not among them). Directional lights are not spread (their position is at infinity); they
// come back unchanged.
std::vector<Light> expandSoftLight(const Light& light);

}  // namespace shadowref
