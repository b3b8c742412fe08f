// `shadowref info SCENE`: what a scene holds, as text — the node tree with world bounding boxes,
// triangles and edge topology per mesh, lights, camera, image and the shadow method. Numbers are
// printed with %g so the text is the same on every machine.
#pragma once

#include <string>
#include <string_view>

#include "scene/scene.h"

namespace shadowref {

// `shadowDetails` describes the settings the scene's shadow technique reads ("silhouette kuhn,
// ..."); the technique knows which (describeShadowSettings in src/shadow/technique_registry.h),
// the scene does not.
std::string describeScene(const Scene& scene, std::string_view shadowDetails = {});

}  // namespace shadowref
