#include "cli/explore_command.h"

#include <CLI/CLI.hpp>

#include "cli/cli_common.h"

namespace shadowref::cli {

void addExploreCommand(CLI::App& app, explore::ExploreOptions& args) {
  CLI::App* cmd = app.add_subcommand(
      "explore",
      "Explore a scene live in the browser (a local web server): camera, lights, methods, views, pixel history");
  cmd->footer("The page orbits, pans and zooms the camera, moves lights (drag a light's marker, or sliders) and "
              "switches them, changes the method and its settings, shows the frame, stencil counts, volumes, depth, "
              "shadow maps (with the camera frustum and TSM's trapezoid), visibility and every pass, and on a click "
              "a pixel's history as render --pixel-history prints it. Each state is a list of -D values: render "
              "with them writes the same pixels. Ctrl-C or SIGTERM stops the server (exit 0).");
  cmd->add_option("scene", args.scene, "Scene file (YAML); omitted: the built-in room");
  cmd->add_option("-D", args.overrides, "Override a scene value, as for render; the page starts from them")
      ->take_all()
      ->allow_extra_args(false);
  cmd->add_option("--host", args.host, "Address to listen on (default 127.0.0.1: this machine only)");
  cmd->add_option("--port", args.port, "Port (default 8080; 0: any free port, printed with the URL)")
      ->check(wholeNumberIn(0, 65535));
  cmd->add_option("--threads", args.threads,
                  "Rasterizer threads (default: every core but one, which the browser needs; 0: every core); the "
                  "pictures do not depend on it")
      ->check(wholeNumberIn(0, 256));
  cmd->add_option("--export", args.exportDir,
                  "Write a self-contained page (views and per-pixel values) into this new or empty folder and "
                  "exit; it opens from the file system with no server");
}

int runExplore(const explore::ExploreOptions& args) {
  // The server starts even when the scene does not load: its page shows the file:line:col message
  // and loads the file again on every change, so that the file can be fixed while the page is open.
  if (!args.exportDir.empty()) return explore::exportPage(args);
  return explore::runExploreServer(args);
}

}  // namespace shadowref::cli
