// `shadowref compare A B`: pixel-by-pixel difference of two images, per channel, with tolerances.
#pragma once

#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace shadowref::cli {

struct CompareArgs {
  std::string a, b;
  double tolerance = 0.0;                // every channel
  std::vector<std::string> channelTolerances;  // "R=0.004", "Z=0"
  std::vector<std::string> channels;     // compare only these (e.g. visibility.L0); empty: all
};

void addCompareCommand(CLI::App& app, CompareArgs& args);
int runCompare(const CompareArgs& args);

}  // namespace shadowref::cli
