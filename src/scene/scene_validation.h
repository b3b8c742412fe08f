// Checks that need the whole scene (after the file, the generator and the -D overrides): the
// image size, the camera's frame, near < far. Each failure points at the key that set the value.
#pragma once

#include "scene/scene.h"
#include "scene/yaml_fields.h"

namespace shadowref {

void validateScene(const Scene& scene, const Provenance& where);

}  // namespace shadowref
