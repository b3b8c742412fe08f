// `shadowref info SCENE`: what a scene holds, as text — the node tree with world bounding boxes,
// triangles and edge topology per mesh, lights, camera, image and the shadow method. Numbers are
// printed with %g so the text is the same on every machine.
#pragma once

#include <string>

#include "scene/scene.h"

namespace shadowref {

std::string describeScene(const Scene& scene);

}  // namespace shadowref
