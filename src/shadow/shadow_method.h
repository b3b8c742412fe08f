// The shadow methods a scene can ask for, by the names the scene file and --method use.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "scene/scene.h"

namespace shadowref {

const char* name(ShadowMethod method);
std::optional<ShadowMethod> parseShadowMethod(std::string_view text);
// "none, zpass, zfail, auto, shadowmap, tsm": for messages and --help.
std::string shadowMethodNames();

}  // namespace shadowref
