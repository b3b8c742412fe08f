// The flat sections of a scene file — image, camera, a light, a material, shadow — each a table
// of keys applied onto an existing object, so that a file can change single fields of what a
// generator made and a -D override single fields of what the file made (docs/scene-format.md).
#pragma once

#include <string>

#include "scene/resource_limits.h"
#include "scene/scene.h"
#include "scene/yaml_fields.h"

namespace shadowref {

void applyImage(const YamlValue& map, Scene& scene, Provenance& where);
void applyCamera(const YamlValue& map, Camera& camera, Provenance& where);
void applyLight(const YamlValue& map, Light& light, const std::string& path, Provenance& where);
void applyMaterial(const YamlValue& map, Material& material, const std::string& path, Provenance& where);
void applyShadow(const YamlValue& map, ShadowSettings& shadow, Provenance& where);
void applyLimits(const YamlValue& map, ResourceLimits& limits, Provenance& where);

// Enum spellings, shared with describeScene so that `info` prints what a file would say.
const EnumNames<LightType>& lightTypeNames();
const EnumNames<SoftShape>& softShapeNames();
const EnumNames<ShadingModel>& shadingNames();
const EnumNames<SilhouetteAlgorithm>& silhouetteNames();
const EnumNames<DepthFormat>& depthFormatNames();

template <class E>
std::string_view enumName(const EnumNames<E>& names, E value) {
  for (const auto& [name, v] : names)
    if (v == value) return name;
  return "?";
}

}  // namespace shadowref
