#include "cli/compare_command.h"

#include <CLI/CLI.hpp>
#include <iostream>
#include <stdexcept>

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
  compare->add_option("--channels", args.channels,
                      "Compare only these channels, e.g. visibility.L0,visibility.L1 (each must be in both images)")
      ->delimiter(',');
}

namespace {

// `image` with only the channels `names`, in that order; a name it lacks is an error naming the
// file and the channels it has.
ChannelImage onlyChannels(const ChannelImage& image, const std::vector<std::string>& names, const std::string& path) {
  ChannelImage out;
  out.width = image.width;
  out.height = image.height;
  for (const std::string& name : names) {
    const int c = image.channelIndex(name);
    if (c < 0) {
      std::string have;
      for (const std::string& n : image.names) have += (have.empty() ? "" : ", ") + n;
      throw std::runtime_error(path + ": no channel '" + name + "' (it has " + have + ")");
    }
    out.names.push_back(name);
    out.data.push_back(image.data[size_t(c)]);
  }
  return out;
}

}  // namespace

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
    CompareResult result;
    if (args.channels.empty()) {
      result = compareImages(args.a, args.b, tol);
    } else {
      result = compareChannelImages(onlyChannels(readChannelImage(args.a), args.channels, args.a),
                                    onlyChannels(readChannelImage(args.b), args.channels, args.b), tol);
      result.nameA = args.a;
      result.nameB = args.b;
    }
    std::cout << formatReport(result);
    return result.passed ? kSuccess : kFailed;
  } catch (const std::exception& e) {
    std::cerr << e.what() << '\n';
    return kBadInput;
  }
}

}  // namespace shadowref::cli
