// The whole command line: every subcommand's options bound to one CommandArgs, the parse, and the
// dispatch to the chosen subcommand. main() is these three calls; the command-line fuzz target
// (fuzz/cli_fuzz.cpp) makes the same calls, so it parses exactly what the program parses.
#pragma once

#include <optional>

#include "cli/bench_command.h"
#include "cli/cli_common.h"
#include "cli/compare_command.h"
#include "cli/explore_command.h"
#include "cli/render_command.h"
#include "cli/sweep_command.h"
#include "cli/replay_command.h"

namespace CLI {
class App;
}

namespace shadowref::cli {

struct CommandArgs {
  RenderArgs render;
  SceneArgs check, info;
  CompareArgs compare;
  BenchArgs bench;
  explore::ExploreOptions explore;
  SweepArgs sweep;
  ReplayArgs replay;
};

// Adds every subcommand to `app`, its options writing into `args` (which must outlive `app`).
void addCommands(CLI::App& app, CommandArgs& args);

// Parses argv. nullopt: run the chosen subcommand; otherwise the exit status (0 after --help or --version,
// kBadInput after a usage error, whose message is already printed).
std::optional<int> parseCommandLine(CLI::App& app, int argc, const char* const* argv);

// Runs the subcommand a successful parse chose.
int runCommand(const CLI::App& app, const CommandArgs& args);

}  // namespace shadowref::cli
