#include "shadow/technique_registry.h"

#include <vector>

#include "scene/yaml_fields.h"

namespace shadowref {

// Each technique is defined in the file of its algorithm. A new one is its file, which defines
// the constant, and its two lines here: the declaration and its place in the table
// (docs/shadow-techniques.md).
extern const ShadowTechnique kUnshadowedTechnique;   // frame_renderer.cpp
extern const ShadowTechnique kZPassTechnique;        // volume_renderer.cpp
extern const ShadowTechnique kZFailTechnique;        // volume_renderer.cpp
extern const ShadowTechnique kAutoTechnique;         // volume_renderer.cpp
extern const ShadowTechnique kShadowMapTechnique;    // shadow_map_renderer.cpp
extern const ShadowTechnique kTrapezoidalTechnique;  // shadow_map_renderer.cpp

namespace {

// In the order of --help and of the messages.
const ShadowTechnique* const kBuiltIn[] = {
    &kUnshadowedTechnique,
    &kZPassTechnique,
    &kZFailTechnique,
    &kAutoTechnique,
    &kShadowMapTechnique,
    &kTrapezoidalTechnique,
};

std::vector<std::string_view> namesOf(TechniqueList among) {
  std::vector<std::string_view> names;
  for (const ShadowTechnique* t : among) names.push_back(t->name);
  return names;
}

}  // namespace

TechniqueList techniques() { return kBuiltIn; }

const ShadowTechnique* findTechnique(std::string_view name, TechniqueList among) {
  for (const ShadowTechnique* t : among)
    if (t->name == name) return t;
  return nullptr;
}

std::string techniqueNames(TechniqueList among) { return joinNames(namesOf(among)); }

std::string unknownTechniqueMessage(std::string_view name, TechniqueList among) {
  const std::vector<std::string_view> names = namesOf(among);
  std::string message = "'" + std::string(name) + "' is not one of " + joinNames(names);
  const std::string_view near = closestName(name, names);
  if (!near.empty()) message += "; did you mean '" + std::string(near) + "'?";
  return message;
}

const ShadowTechnique& techniqueOf(const ShadowSettings& settings, TechniqueList among) {
  if (const ShadowTechnique* t = findTechnique(settings.method, among)) return *t;
  throw SceneError(settings.methodAt, "shadow.method: " + unknownTechniqueMessage(settings.method, among));
}

std::string describeShadowSettings(const ShadowSettings& settings, TechniqueList among) {
  const ShadowTechnique* t = findTechnique(settings.method, among);
  return t && t->describe ? t->describe(settings) : std::string();
}

}  // namespace shadowref
