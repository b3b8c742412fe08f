// `shadowref check SCENE` (validate only) and `shadowref info SCENE` (what the scene holds).
#pragma once

#include "cli/cli_common.h"

namespace CLI {
class App;
}

namespace shadowref::cli {

void addCheckCommand(CLI::App& app, SceneArgs& args);
void addInfoCommand(CLI::App& app, SceneArgs& args);
int runCheck(const SceneArgs& args);
int runInfo(const SceneArgs& args);

}  // namespace shadowref::cli
