// Checks that need the whole scene (after the file, the generator and the -D overrides): the
// image size, the camera's frame and matrices, near < far, the lights' derived positions and
// directions, every node's world transform, and the resource budget (instances, triangles and
// vertices after instancing, counted without flattening). Each failure points at the key or node
// that set the value.
#pragma once

#include "scene/resource_limits.h"
#include "scene/scene.h"
#include "scene/yaml_fields.h"

namespace shadowref {

void validateScene(const Scene& scene, const ResourceLimits& limits, const Provenance& where);

}  // namespace shadowref
