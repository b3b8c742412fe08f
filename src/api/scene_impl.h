// What a shadowref::api::Scene holds: the loaded scene and how it was named and overridden (for
// the metadata of the images writeImage writes). Shared by the library and the Python module,
// which reaches the scene itself for the ray-cast oracle.
#pragma once

#include <string>
#include <vector>

#include "scene/scene.h"
#include "shadowref/shadowref.h"

namespace shadowref::api {

struct Scene::Impl {
  shadowref::Scene scene;
  std::string name;                    // the file as given, or the name given with the string
  std::vector<std::string> overrides;  // as given
};

}  // namespace shadowref::api
