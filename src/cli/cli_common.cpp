#include "cli/cli_common.h"

#include <filesystem>
#include <iostream>

#include "scene/scene_error.h"
#include "scene/scene_loader.h"
#include "shadow/shadow_method.h"

namespace shadowref::cli {

std::optional<Scene> loadSceneOrReport(const SceneArgs& args) {
  try {
    LoadOptions options;
    options.overrides = args.overrides;
    if (args.scene.empty()) {
      // The built-in default is the room of [Kuhn 2016, Fig. 5.1] with z-fail shadow volumes
      // (scenes/room.yaml says the same at length), as a two-line scene, so that -D overrides work
      // on it exactly as on a file.
      return loadSceneFromString("generator: {type: room}\nshadow: {method: zfail}\n", "<builtin:room>", options);
    }
    return loadScene(args.scene, options);
  } catch (const SceneError& e) {
    std::cerr << e.what() << '\n';
  } catch (const std::exception& e) {
    std::cerr << (args.scene.empty() ? "<builtin:room>" : args.scene) << ": " << e.what() << '\n';
  }
  return std::nullopt;
}

bool parseMethodOrReport(const std::string& text, std::optional<ShadowMethod>& method) {
  if (text.empty()) return true;
  method = parseShadowMethod(text);
  if (method) return true;
  std::cerr << "--method: unknown method '" << text << "' (expected one of " << shadowMethodNames() << ")\n";
  return false;
}

std::string defaultOutputPath(const std::string& scenePath, const std::string& extension) {
  const std::string stem = scenePath.empty() ? "default" : std::filesystem::path(scenePath).stem().string();
  return "out/" + stem + extension;
}

void ensureParentDirectory(const std::string& path) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
}

}  // namespace shadowref::cli
