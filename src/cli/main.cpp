// shadowref: a deterministic reference rasterizer for the classic shadow algorithms.
#include <CLI/CLI.hpp>
#include <iostream>

#include "cli/bench_command.h"
#include "cli/cli_common.h"
#include "cli/compare_command.h"
#include "cli/render_command.h"
#include "cli/scene_commands.h"
#include "cli/version_info.h"
#include "image/atomic_write.h"

int main(int argc, char** argv) {
  using namespace shadowref::cli;
  CLI::App app{"shadowref: a deterministic software rasterizer with colour, depth, stencil and accumulation\n"
               "buffers, on which stencil shadow volumes and shadow maps run exactly as their sources describe."};
  app.require_subcommand(1);
  app.set_version_flag("--version", versionText(),
                       "Print the version, git revision, vector level and compiler of this build and exit");
  RenderArgs render;
  SceneArgs check, info;
  CompareArgs compare;
  BenchArgs bench;
  addRenderCommand(app, render);
  addCheckCommand(app, check);
  addInfoCommand(app, info);
  addCompareCommand(app, compare);
  addBenchCommand(app, bench);
  app.footer("Exit status: 0 success, 1 a failed render or comparison, 2 bad usage or bad input.");
  // Ctrl-C or kill during a write removes the temporary file (the target is never damaged anyway).
  shadowref::removeTempFilesOnSignals();
  if (reportUnknownSubcommand(app, argc, argv)) return kBadInput;
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kBadInput;
  }
  if (app.got_subcommand("render")) return runRender(render);
  if (app.got_subcommand("check")) return runCheck(check);
  if (app.got_subcommand("info")) return runInfo(info);
  if (app.got_subcommand("compare")) return runCompare(compare);
  if (app.got_subcommand("bench")) return runBench(bench);
  return kBadInput;
}
