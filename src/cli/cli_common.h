// What every subcommand shares: exit codes, loading a scene with clear errors, output paths.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace CLI {
class App;
class Validator;
}

namespace shadowref::cli {

// Exit status: 0 success, 1 a failed render or comparison, 2 bad usage or bad input.
enum ExitCode : int { kSuccess = 0, kFailed = 1, kBadInput = 2 };

struct SceneArgs {
  std::string scene;                   // empty: the built-in default scene (the room)
  std::vector<std::string> overrides;  // -D key=value
};

// Loads the scene (or builds the default one), applies overrides and checks that its shadow.method
// names a technique. A SceneError is printed as "file:line:col: message" on stderr and returns
// nullopt.
std::optional<Scene> loadSceneOrReport(const SceneArgs& args);

// --method: empty keeps the scene's method; an unknown name is reported on stderr (false).
bool checkMethodOrReport(const std::string& text);

// "Shadow method: none, zpass, ...": --method's help, from the registry.
std::string methodHelp();

// "out/room.png" for "scenes/room.yaml", "out/default.png" for the built-in scene.
std::string defaultOutputPath(const std::string& scenePath, const std::string& extension);

// When argv[1] is a word that names no subcommand of app, prints "unknown subcommand 'rendr' (did
// you mean 'render'?)" and returns true: CLI11 would only say that a subcommand is required.
bool reportUnknownSubcommand(const CLI::App& app, int argc, const char* const* argv);

// A check for an integer flag that tells "abc" (not a whole number) from "-1" (outside min to max,
// both allowed); CLI::Range says "not in range" for both.
CLI::Validator wholeNumberIn(int min, int max);

// Creates the missing parent folders of `path`, appending each one it made to `made` (outermost
// first) when given, so that a failed command can take them away again (removeEmptyFolders).
void ensureParentDirectory(const std::string& path, std::vector<std::string>* made = nullptr);

// Removes the folders of `made` that are empty, innermost first: what a failed command made and
// did not fill.
void removeEmptyFolders(const std::vector<std::string>& made);

// Why the parent folders of `path` can neither be found nor made (a part of the path is a file),
// or "" when they exist or can be made. Checked before rendering, so that such an -o is bad usage
// (exit 2), found before any work is done.
std::string outputFolderProblem(const std::string& path);

}  // namespace shadowref::cli
