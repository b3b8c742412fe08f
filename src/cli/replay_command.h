// `shadowref replay frame.srtrace --on TARGET`: a captured frame (render --capture) run again on
// shadowref's pipelines or on Mesa through OSMesa, every buffer compared and the differing pixels
// classified (src/trace).
#pragma once

#include <string>

namespace CLI {
class App;
}

namespace shadowref::cli {

struct ReplayArgs {
  std::string trace;
  std::string on = "reference";
  std::string against = "trace";
  std::string report;  // folder for index.html and pictures; empty: none
  int threads = 0;
  unsigned depthTolerance = 2;
};

void addReplayCommand(CLI::App& app, ReplayArgs& args);
int runReplay(const ReplayArgs& args);

}  // namespace shadowref::cli
