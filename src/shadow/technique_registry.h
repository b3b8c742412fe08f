// The shadow techniques this build renders, by name: the one list the scene file's
// shadow.method, --method, --help and `shadowref info` draw on (docs/shadow-techniques.md says
// how to add one).
#pragma once

#include <span>
#include <string>
#include <string_view>

#include "scene/scene.h"
#include "shadow/technique.h"

namespace shadowref {

using TechniqueList = std::span<const ShadowTechnique* const>;

// Every built-in technique, in the order of --help: none, zpass, zfail, auto, shadowmap, tsm.
TechniqueList techniques();

// The technique of that name among `among`, or nullptr.
const ShadowTechnique* findTechnique(std::string_view name, TechniqueList among = techniques());

// "none, zpass, zfail, auto, shadowmap, tsm": the names for messages and --help.
std::string techniqueNames(TechniqueList among = techniques());

// "'zfial' is not one of none, zpass, ...; did you mean 'zfail'?": the message for a name that
// names no technique.
std::string unknownTechniqueMessage(std::string_view name, TechniqueList among = techniques());

// The technique the scene's shadow.method names; for an unknown name a SceneError at
// settings.methodAt: "t.yaml:2:11: shadow.method: 'zfial' is not one of ...".
const ShadowTechnique& techniqueOf(const ShadowSettings& settings, TechniqueList among = techniques());

// The details `shadowref info` prints after the technique's name: its describe(), or "" when it
// has none or the name is unknown.
std::string describeShadowSettings(const ShadowSettings& settings, TechniqueList among = techniques());

}  // namespace shadowref
