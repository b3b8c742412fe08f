// `shadowref explore [SCENE]`: the interactive shadow lab in the browser (src/explore/).
#pragma once

#include "explore/explore_server.h"

namespace CLI {
class App;
}

namespace shadowref::cli {

void addExploreCommand(CLI::App& app, explore::ExploreOptions& args);
int runExplore(const explore::ExploreOptions& args);

}  // namespace shadowref::cli
