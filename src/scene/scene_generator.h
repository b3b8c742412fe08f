// The `generator:` section: one of the documents' test scenes (room, pumpkins, city, outdoor) with
// its options, built before the rest of the file is applied on top of it.
#pragma once

#include <string>

#include "scene/scene.h"
#include "scene/yaml_fields.h"

namespace shadowref {

// `generator: city` is short for `generator: {type: city}`.
YamlValue generatorShorthand(const YamlValue& scalar);

// Runs the generator that `section` names with its options on `scene`.
void runGenerator(const YamlValue& section, Scene& scene, Provenance& where);

}  // namespace shadowref
