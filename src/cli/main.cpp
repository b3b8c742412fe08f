// shadowref: a deterministic reference rasterizer for the classic shadow algorithms.
#include <CLI/CLI.hpp>

#include "cli/command_line.h"
#include "cli/explore_handover.h"
#include "cli/gl_handover.h"
#include "image/atomic_write.h"

int main(int argc, char** argv) {
  using namespace shadowref::cli;
  handOverToGlProgram(argc, argv);
#ifndef SHADOWREF_EXPLORE_PROGRAM  // shadowref-explore runs `explore` itself
  handOverToExploreProgram(argc, argv);
#endif
  CLI::App app;
  CommandArgs args;
  addCommands(app, args);
  // Ctrl-C or kill during a write removes the temporary file (the target is never damaged anyway).
  shadowref::removeTempFilesOnSignals();
  if (const std::optional<int> status = parseCommandLine(app, argc, argv)) return *status;
  return runCommand(app, args);
}
