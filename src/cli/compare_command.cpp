#include "cli/compare_command.h"

#include <CLI/CLI.hpp>
#include <iostream>

#include "cli/cli_common.h"
#include "image/image_compare.h"

namespace shadowref::cli {

void addCompareCommand(CLI::App& app, CompareArgs& args) {
  CLI::App* compare = app.add_subcommand("compare", "Compare two images pixel by pixel, per channel (exit 1 if they differ)");
  compare->add_option("a", args.a, "First image")->required();
  compare->add_option("b", args.b, "Second image")->required();
  compare->add_option("--tolerance", args.tolerance, "Absolute tolerance for every channel (default 0)")
      ->check(CLI::NonNegativeNumber);
  compare->add_option("--channel-tolerance", args.channelTolerances, "NAME=VALUE: tolerance for one channel, repeatable");
}

int runCompare(const CompareArgs& args) {
  Tolerances tol;
  tol.fallback = args.tolerance;
  for (const std::string& spec : args.channelTolerances) {
    const size_t eq = spec.find('=');
    try {
      size_t used = 0;
      if (eq == std::string::npos || eq == 0) throw std::invalid_argument("");
      const double value = std::stod(spec.substr(eq + 1), &used);
      if (used != spec.size() - eq - 1 || !(value >= 0.0)) throw std::invalid_argument("");
      tol.perChannel[spec.substr(0, eq)] = value;
    } catch (const std::exception&) {
      std::cerr << "--channel-tolerance: expected NAME=VALUE with VALUE >= 0, got '" << spec << "'\n";
      return kBadInput;
    }
  }
  try {
    const CompareResult result = compareImages(args.a, args.b, tol);
    std::cout << formatReport(result);
    return result.passed ? kSuccess : kFailed;
  } catch (const std::exception& e) {
    std::cerr << e.what() << '\n';
    return kBadInput;
  }
}

}  // namespace shadowref::cli
