// `shadowref render [SCENE] [-o OUT]...`: renders a scene to PNG and/or EXR, with the teaching dumps.
#pragma once

#include <string>
#include <vector>

#include "cli/cli_common.h"

namespace CLI {
class App;
}

namespace shadowref::cli {

struct RenderArgs {
  SceneArgs scene;
  std::vector<std::string> outputs;  // .png / .exr
  std::string method;                // overrides shadow.method
  int threads = 0;                   // 0: all cores
  std::string pipeline = "fast";     // reference, fast
  bool quiet = false;
  bool stats = false;
  std::vector<std::string> dumps;    // passes, stencil, depth
  std::string dumpRegion;            // "x,y,w,h": stencil counts of that region as a grid
  std::string view;                  // volumes, volumes-overlay
  std::string pixelHistory;          // "x,y"
  std::string capture;               // trace file of the frame's commands (src/trace)
};

void addRenderCommand(CLI::App& app, RenderArgs& args);
int runRender(const RenderArgs& args);

}  // namespace shadowref::cli
