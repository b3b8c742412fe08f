// `shadowref compare A B`: pixel-by-pixel difference of two images, per channel, with tolerances,
// idiff's thresholds and exit codes, a heat map of the difference and a JSON report.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace shadowref::cli {

// compare's exit status, idiff's: 0 PASS, 1 WARNING, 2 FAILURE, 3 sizes or channel sets differ,
// 4 bad input (an image that cannot be read, a bad option or value). Bad input is not 2 here, as
// for the other subcommands, because 2 is idiff's FAILURE.
enum CompareExit : int { kComparePass = 0, kCompareWarn = 1, kCompareFail = 2, kCompareMismatch = 3, kCompareBadInput = 4 };

struct CompareArgs {
  std::string a, b;
  double tolerance = 0.0;                // every channel (--fail)
  std::vector<std::string> channelTolerances;  // "R=0.004", "Z=0"
  std::vector<std::string> channels;     // compare only these (e.g. visibility.L0); empty: all
  double failPercent = 0.0;
  double hardFail = std::numeric_limits<double>::infinity();
  size_t allowFailures = 0;
  double warn = -1.0;                    // negative: each channel's tolerance
  double warnPercent = 0.0;
  double hardWarn = std::numeric_limits<double>::infinity();
  uint32_t modulo = 0;                   // integer channels modulo this; 0: as they are
  std::string diff;                      // heat map PNG
  std::string diffChannel;               // "": combined
  double diffScale = 0.0;                // the top of the heat map's scale; 0: the largest difference
  bool diffOnlyIfDifferent = false;
  bool json = false;
};

void addCompareCommand(CLI::App& app, CompareArgs& args);
int runCompare(const CompareArgs& args);

// The exit status of a command line CLI11 refused: compare's bad input (4) when the subcommand is
// compare, otherwise the common bad-usage status (2).
int badUsageExit(int argc, const char* const* argv);

}  // namespace shadowref::cli
