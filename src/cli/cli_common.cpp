#include "cli/cli_common.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <charconv>
#include <filesystem>
#include <iostream>
#include <stdexcept>

#include "scene/scene_error.h"
#include "scene/scene_loader.h"
#include "scene/yaml_fields.h"
#include "shadow/technique_registry.h"

namespace shadowref::cli {

std::optional<Scene> loadSceneOrReport(const SceneArgs& args) {
  try {
    LoadOptions options;
    options.overrides = args.overrides;
    // The built-in default is the room of [Kuhn 2016, Fig. 5.1] with z-fail shadow volumes
    // (scenes/room.yaml says the same at length), as a two-line scene, so that -D overrides work
    // on it exactly as on a file.
    Scene scene = args.scene.empty()
                      ? loadSceneFromString("generator: {type: room}\nshadow: {method: zfail}\n", "<builtin:room>", options)
                      : loadScene(args.scene, options);
    // The loader takes any name; the registry knows the techniques. Checked here, so that
    // `check` and `info` report an unknown one as a render would, at the same file:line:col.
    techniqueOf(scene.shadow);
    return scene;
  } catch (const SceneError& e) {
    std::cerr << e.what() << '\n';
  } catch (const std::exception& e) {
    std::cerr << (args.scene.empty() ? "<builtin:room>" : args.scene) << ": " << e.what() << '\n';
  }
  return std::nullopt;
}

bool checkMethodOrReport(const std::string& text) {
  if (text.empty() || findTechnique(text)) return true;
  std::cerr << "--method: unknown method '" << text << "' (expected one of " << techniqueNames() << ")\n";
  return false;
}

std::string methodHelp() { return "Shadow method: " + techniqueNames(); }

std::string defaultOutputPath(const std::string& scenePath, const std::string& extension) {
  const std::string stem = scenePath.empty() ? "default" : std::filesystem::path(scenePath).stem().string();
  return "out/" + stem + extension;
}

bool reportUnknownSubcommand(const CLI::App& app, int argc, const char* const* argv) {
  if (argc < 2 || argv[1][0] == '-' || argv[1][0] == '\0') return false;
  const std::string word = argv[1];
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) names.push_back(sub->get_name());
  if (std::find(names.begin(), names.end(), word) != names.end()) return false;
  const std::vector<std::string_view> candidates(names.begin(), names.end());
  const std::string best(closestName(word, candidates));  // the scene file's "did you mean", too
  std::cerr << "unknown subcommand '" << word << "'";
  if (!best.empty()) std::cerr << " (did you mean '" << best << "'?)";
  std::cerr << "; the subcommands are";
  for (const std::string& name : names) std::cerr << ' ' << name;
  std::cerr << "\n";
  return true;
}

CLI::Validator wholeNumberIn(int min, int max) {
  const std::string range = std::to_string(min) + " to " + std::to_string(max);
  return CLI::Validator(
      [min, max, range](std::string& text) -> std::string {
        long long value = 0;
        const char* end = text.data() + text.size();
        const auto [stop, ec] = std::from_chars(text.data(), end, value);
        if (text.empty() || (ec != std::errc() && ec != std::errc::result_out_of_range) || stop != end)
          return "'" + text + "' is not a whole number (allowed: " + range + ")";
        if (ec == std::errc::result_out_of_range || value < min || value > max)
          return text + " is outside the allowed range " + range;
        return "";
      },
      "INT in " + range);
}

void ensureParentDirectory(const std::string& path, std::vector<std::string>* made) {
  namespace fs = std::filesystem;
  const fs::path parent = fs::path(path).parent_path();
  if (parent.empty()) return;
  // The missing folders, innermost first, then made outermost first.
  std::vector<fs::path> missing;
  std::error_code ec;
  for (fs::path p = parent; !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
    missing.push_back(p);
    if (p == p.parent_path()) break;
  }
  for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
    if (fs::create_directory(*it) && made) made->push_back(it->string());
  }
  if (!fs::is_directory(parent)) throw std::runtime_error(parent.string() + " is not a folder");
}

void removeEmptyFolders(const std::vector<std::string>& made) {
  for (auto it = made.rbegin(); it != made.rend(); ++it) {
    std::error_code ec;
    if (std::filesystem::is_empty(*it, ec) && !ec) std::filesystem::remove(*it, ec);
  }
}

std::string outputFolderProblem(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  // The nearest part of the folder path that exists must be a folder.
  for (fs::path p = fs::path(path).parent_path(); !p.empty(); p = p.parent_path()) {
    const fs::file_status status = fs::status(p, ec);
    if (fs::exists(status)) {
      if (!fs::is_directory(status)) return "'" + p.string() + "' is not a folder, so no folder can be made in it";
      return "";
    }
    if (p == p.parent_path()) break;
  }
  return "";
}

}  // namespace shadowref::cli
