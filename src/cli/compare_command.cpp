#include "cli/compare_command.h"

#include <CLI/CLI.hpp>
#include <cstring>
#include <iostream>
#include <stdexcept>

#include "cli/cli_common.h"
#include "image/difference_image.h"
#include "image/image_compare.h"

namespace shadowref::cli {

void addCompareCommand(CLI::App& app, CompareArgs& args) {
  CLI::App* compare = app.add_subcommand(
      "compare",
      "Compare two images pixel by pixel, per channel, as idiff does; 32-bit integer channels (stencil) as integers");
  compare->add_option("a", args.a, "First image")->required();
  compare->add_option("b", args.b, "Second image")->required();
  compare->add_option("--fail,--tolerance", args.tolerance,
                      "A pixel fails where a channel differs by more than this (absolute; default 0: exact)")
      ->check(CLI::NonNegativeNumber);
  compare->add_option("--channel-tolerance", args.channelTolerances, "NAME=VALUE: tolerance for one channel, repeatable");
  compare->add_option("--fail-percent", args.failPercent,
                      "FAILURE only when more than this percentage of pixels fail (default 0)")
      ->check(CLI::Range(0.0, 100.0));
  compare->add_option("--hard-fail", args.hardFail, "FAILURE when any difference exceeds this, whatever the share")
      ->check(CLI::NonNegativeNumber);
  compare->add_option("--allow-failures", args.allowFailures, "Up to this many failing pixels are not a FAILURE");
  compare->add_option("--warn", args.warn,
                      "Warning level: a pixel is over it where a channel differs by more (default: the tolerance)")
      ->check(CLI::NonNegativeNumber);
  compare->add_option("--warn-percent", args.warnPercent,
                      "WARNING only when more than this percentage of pixels are over the warning level (default 0)")
      ->check(CLI::Range(0.0, 100.0));
  compare->add_option("--hard-warn", args.hardWarn, "WARNING when any difference exceeds this")
      ->check(CLI::NonNegativeNumber);
  compare->add_option("--channels", args.channels,
                      "Compare only these channels, e.g. visibility.L0,visibility.L1 (each must be in both images)")
      ->delimiter(',');
  compare->add_option("--modulo", args.modulo,
                      "Compare integer channels modulo N, e.g. 256 for an 8-bit stencil buffer (a count of 257 is 1)")
      ->check(CLI::Range(uint32_t(1), std::numeric_limits<uint32_t>::max()));
  compare->add_option("--diff", args.diff,
                      "Write the difference as a heat map PNG with its colour scale (black: equal; white: the top)");
  compare->add_option("--diff-channel", args.diffChannel,
                      "Draw only this channel's difference (default: the largest over the compared channels)");
  compare->add_option("--diff-scale", args.diffScale,
                      "The difference at the top of the heat map's scale (default: the largest difference)")
      ->check(CLI::PositiveNumber);
  compare->add_flag("--diff-only-if-different", args.diffOnlyIfDifferent,
                    "Write --diff only when some pixel differs");
  compare->add_flag("--json", args.json, "Print the report as JSON (verdict, per channel every metric)");
  compare->footer(
      "Per channel: max and mean |A-B|, RMSE, PSNR, pixels over the tolerance. Exit status (idiff's): 0 PASS,\n"
      "1 WARNING, 2 FAILURE, 3 the sizes or channel sets differ, 4 bad input (unreadable image, bad option).");
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
    out.integer.push_back(image.isInteger(size_t(c)));
  }
  return out;
}

int exitFor(const CompareResult& r) {
  if (!r.structuralError.empty()) return kCompareMismatch;
  switch (r.verdict) {
    case Verdict::Pass: return kComparePass;
    case Verdict::Warn: return kCompareWarn;
    case Verdict::Fail: return kCompareFail;
  }
  return kCompareFail;
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
      return kCompareBadInput;
    }
  }
  tol.warn = args.warn;
  tol.failPercent = args.failPercent;
  tol.warnPercent = args.warnPercent;
  tol.hardFail = args.hardFail;
  tol.hardWarn = args.hardWarn;
  tol.allowFailures = args.allowFailures;
  tol.integerModulo = args.modulo;
  if (!args.diff.empty()) {
    if (const std::string problem = outputFolderProblem(args.diff); !problem.empty()) {
      std::cerr << "--diff: " << problem << '\n';
      return kCompareBadInput;
    }
  }
  ChannelImage a, b;
  try {
    a = readChannelImage(args.a);
    b = readChannelImage(args.b);
    if (!args.channels.empty()) {
      a = onlyChannels(a, args.channels, args.a);
      b = onlyChannels(b, args.channels, args.b);
    }
    if (!args.diffChannel.empty() && a.channelIndex(args.diffChannel) < 0)
      throw std::runtime_error("--diff-channel: '" + args.diffChannel + "' is not among the compared channels");
  } catch (const std::exception& e) {
    std::cerr << e.what() << '\n';
    return kCompareBadInput;
  }
  CompareResult result = compareChannelImages(a, b, tol);
  result.nameA = args.a;
  result.nameB = args.b;
  std::cout << (args.json ? formatJson(result) : formatReport(result));
  const int status = exitFor(result);
  if (!args.diff.empty() && status != kCompareMismatch) {
    bool differs = false;
    for (const ChannelStats& s : result.channels) differs = differs || s.maxAbsDiff > 0.0;
    if (differs || !args.diffOnlyIfDifferent) {
      std::vector<std::string> made;
      try {
        DifferenceMapOptions options;
        options.channel = args.diffChannel;
        options.integerModulo = args.modulo;
        const std::vector<double> diffs = differenceMap(a, b, options);
        ensureParentDirectory(args.diff, &made);
        writePng8(differenceHeatMap(diffs, a.width, a.height, args.diffScale), args.diff);
        if (!args.json) std::cout << "difference picture: " << args.diff << '\n';
      } catch (const std::exception& e) {
        removeEmptyFolders(made);  // the picture is written whole or not at all; so are its folders
        std::cerr << "--diff: " << e.what() << '\n';
        return kCompareBadInput;
      }
    }
  }
  return status;
}

int badUsageExit(int argc, const char* const* argv) {
  // The subcommand is the first argument that is not an option (options before it are global).
  for (int i = 1; i < argc; ++i) {
    if (argv[i][0] == '-') continue;
    return std::strcmp(argv[i], "compare") == 0 ? int(kCompareBadInput) : int(kBadInput);
  }
  return kBadInput;
}

}  // namespace shadowref::cli
