#include "cli/command_line.h"

#include <CLI/CLI.hpp>

#include "cli/scene_commands.h"
#include "cli/version_info.h"

namespace shadowref::cli {

void addCommands(CLI::App& app, CommandArgs& args) {
  app.description("shadowref: a deterministic software rasterizer with colour, depth, stencil and accumulation\n"
                  "buffers, on which stencil shadow volumes and shadow maps run exactly as their sources describe.");
  app.require_subcommand(1);
  app.set_version_flag("--version", versionText(),
                       "Print the version, git revision, vector level and compiler of this build and exit");
  addRenderCommand(app, args.render);
  addCheckCommand(app, args.check);
  addInfoCommand(app, args.info);
  addCompareCommand(app, args.compare);
  addBenchCommand(app, args.bench);
  addExploreCommand(app, args.explore);
  addSweepCommand(app, args.sweep);
  addReplayCommand(app, args.replay);
  app.footer("Exit status: 0 success, 1 a failed render, 2 bad usage or bad input; compare has idiff's:\n"
             "0 PASS, 1 WARNING, 2 FAILURE, 3 sizes or channels differ, 4 bad input;\n"
             "130 / 143 after SIGINT / SIGTERM, which remove any half-written temporary file\n"
             "(explore: SIGINT and SIGTERM are how its server stops, with 0).");
}

std::optional<int> parseCommandLine(CLI::App& app, int argc, const char* const* argv) {
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
    return badUsageExit(argc, argv);
  }
  return std::nullopt;
}

int runCommand(const CLI::App& app, const CommandArgs& args) {
  if (app.got_subcommand("render")) return runRender(args.render);
  if (app.got_subcommand("check")) return runCheck(args.check);
  if (app.got_subcommand("info")) return runInfo(args.info);
  if (app.got_subcommand("compare")) return runCompare(args.compare);
  if (app.got_subcommand("bench")) return runBench(args.bench);
  if (app.got_subcommand("explore")) return runExplore(args.explore);
  if (app.got_subcommand("sweep")) return runSweep(args.sweep);
  if (app.got_subcommand("replay")) return runReplay(args.replay);
  return kBadInput;
}

}  // namespace shadowref::cli
