#include "cli/scene_commands.h"

#include <CLI/CLI.hpp>
#include <iostream>

#include "scene/scene_info.h"
#include "shadow/technique_registry.h"

namespace shadowref::cli {

void addCheckCommand(CLI::App& app, SceneArgs& args) {
  CLI::App* check = app.add_subcommand("check", "Validate a scene file: exit 0, or the errors and exit 2");
  check->add_option("scene", args.scene, "Scene file (YAML)")->required();
  // One value per -D, so that a -D before the scene does not swallow it (as in render).
  check->add_option("-D", args.overrides, "Override a scene value, e.g. -D camera.near=0.001")
      ->take_all()
      ->allow_extra_args(false);
}

void addInfoCommand(CLI::App& app, SceneArgs& args) {
  CLI::App* info = app.add_subcommand("info", "Print what a scene holds: nodes, meshes, edges, lights, bounds");
  info->add_option("scene", args.scene, "Scene file (YAML); omitted: the built-in room");
  info->add_option("-D", args.overrides, "Override a scene value, e.g. -D camera.near=0.001")
      ->take_all()
      ->allow_extra_args(false);
}

int runCheck(const SceneArgs& args) {
  return loadSceneOrReport(args) ? kSuccess : kBadInput;
}

int runInfo(const SceneArgs& args) {
  const std::optional<Scene> scene = loadSceneOrReport(args);
  if (!scene) return kBadInput;
  std::cout << describeScene(*scene, describeShadowSettings(scene->shadow));
  return kSuccess;
}

}  // namespace shadowref::cli
