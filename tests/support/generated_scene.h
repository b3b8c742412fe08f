// One of the built-in generated scenes (room, pumpkins, city, outdoor) at a given size and with a
// given shadow method, for tests that render whole frames.
#pragma once

#include <string>

#include "scene/scene.h"

namespace shadowref::testing {

Scene generatedScene(const std::string& generator, const std::string& method, int width, int height);

}  // namespace shadowref::testing
