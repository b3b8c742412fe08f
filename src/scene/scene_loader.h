// Reads a scene file (YAML, docs/scene-format.md) into the scene model, applies -D overrides and
// checks the result. Any problem is a SceneError "file:line:column: message"; nothing is
// returned half-built.
#pragma once

#include <string>
#include <vector>

#include "scene/scene.h"
#include "scene/scene_error.h"

namespace shadowref {

struct LoadOptions {
  // "-D key=value" overrides in command-line order, e.g. "camera.near=0.001", "lights.0.range=5",
  // "shadow.method=zfail". Errors in the i-th one are reported at "<command line>:i:column".
  std::vector<std::string> overrides;
};

inline constexpr const char* kCommandLineFile = "<command line>";

// Mesh file paths in the scene are relative to the scene file's folder.
Scene loadScene(const std::string& path, const LoadOptions& options = {});

// `displayName` appears in messages; mesh file paths are relative to the current directory.
Scene loadSceneFromString(const std::string& yaml, const std::string& displayName,
                          const LoadOptions& options = {});

}  // namespace shadowref
