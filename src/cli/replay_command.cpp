#include "cli/replay_command.h"

#include <CLI/CLI.hpp>

#include <iostream>

#include "cli/cli_common.h"
#include "trace/replay_target.h"
#include "trace/trace_compare.h"
#include "trace/trace_file.h"

namespace shadowref::cli {

void addReplayCommand(CLI::App& app, ReplayArgs& args) {
  CLI::App* replay = app.add_subcommand(
      "replay", "Run a captured frame (render --capture) again and compare every buffer; exit 1 when they differ");
  replay->add_option("trace", args.trace, "The trace file (.srtrace, docs/trace-format.md)")->required();
  replay->add_option("--on", args.on,
                     "Where to run it: 'reference' (default), 'fast', 'osmesa:llvmpipe' or 'osmesa:softpipe' (Mesa, "
                     "in a build with OSMesa), 'egl:llvmpipe' or 'egl:softpipe' (Mesa through EGL's surfaceless "
                     "platform, in a build with OSMesa and EGL; no accumulation buffer)")
      ->check(CLI::IsMember(trace::replayTargetNames()));
  replay->add_option("--against", args.against,
                     "What to compare with: 'trace' (default: the buffers recorded in the trace, byte for byte; "
                     "for an OSMesa or EGL target the reference in fixed-function mode) or another --on target")
      ->check(CLI::IsMember([] {
        std::vector<std::string> names = {"trace"};
        for (const std::string& n : trace::replayTargetNames()) names.push_back(n);
        return names;
      }()));
  replay->add_option("--report", args.report,
                     "Folder for index.html with the expected, actual and difference pictures of every buffer");
  replay->add_option("--threads", args.threads, "Threads of the fast pipeline (0: one per CPU)")
      ->check(wholeNumberIn(0, 256));
  replay->add_option("--depth-tolerance", args.depthTolerance,
                     "Against a real GL: 24-bit depth codes that may differ off the edges (default 2), plus the "
                     "largest polygon offset units of the framebuffer's draws (Mesa doubles them) and 1 if it has any (Mesa "
                     "adds the offset in float; docs/conformance.md)")
      ->check(CLI::Range(0u, 1u << 24));
}

int runReplay(const ReplayArgs& args) {
  using namespace trace;
  Trace t;
  try {
    t = readTraceFile(args.trace);
  } catch (const std::exception& e) {
    std::cerr << args.trace << ": " << e.what() << '\n';
    return kBadInput;
  }
  const ReplayTarget on = *parseReplayTarget(args.on);
  const std::optional<ReplayTarget> against =
      args.against == "trace" ? (on.gl ? parseReplayTarget("reference") : std::nullopt) : parseReplayTarget(args.against);
  if (on.gl && against && against->gl && on.driver != against->driver) {
    // Mesa picks its driver once per process, at the first context.
    std::cerr << "replay: --on " << on.name << " and --against " << against->name
              << " need two processes (Mesa's driver is chosen once per process); compare each with the reference\n";
    return kBadInput;
  }
  if ((on.gl || (against && against->gl)) && !osmesaAvailable()) {
    std::cerr << "replay: this build has no OSMesa (install libosmesa6-dev and rebuild)\n";
    return kBadInput;
  }
  if ((on.api == "egl" || (against && against->api == "egl")) && !eglAvailable()) {
    std::cerr << "replay: this build has no EGL (install libegl-dev and libegl-mesa0 and rebuild)\n";
    return kBadInput;
  }
  // A real GL on either side: both replay in the fixed-function mode and may differ as
  // docs/conformance.md allows; otherwise byte for byte.
  const bool gl = on.gl || (against && against->gl);
  const ReplayMode mode = gl ? ReplayMode::FixedFunction : ReplayMode::Exact;
  try {
    const ReplayResult actual = replayOn(t, on, mode, args.threads);
    ReplayResult other;
    std::vector<const Buffers*> expected;
    std::string expectedName;
    if (against) {
      other = replayOn(t, *against, mode, args.threads);
      for (const Buffers& b : other.buffers) expected.push_back(&b);
      expectedName = against->name + (gl ? " (fixed-function mode)" : "");
    } else {
      for (const std::optional<Buffers>& b : t.results) expected.push_back(b ? &*b : nullptr);
      expectedName = "the buffers recorded in " + args.trace;
    }
    std::vector<Tolerances> tolerances(t.targets.size());
    for (uint32_t i = 0; i < tolerances.size(); ++i) {
      tolerances[i].exact = !gl;
      tolerances[i].colorTolerance255 = fixedFunctionColorTolerance(t, i);
      tolerances[i].depthTolerance = fixedFunctionDepthTolerance(t, i, args.depthTolerance);
    }
    Comparison c = compareBuffers(t, expected, actual.buffers, tolerances);
    c.expectedName = expectedName;
    c.actualName = on.name + (gl ? " (fixed-function mode)" : "");
    std::cout << reportText(c);
    if (!args.report.empty()) {
      writeReportHtml(c, expected, actual.buffers, args.report);
      std::cerr << "wrote " << args.report << "/index.html\n";
    }
    return c.passes() ? kSuccess : kFailed;
  } catch (const std::exception& e) {
    std::cerr << "replay: " << e.what() << '\n';
    return kFailed;
  }
}

}  // namespace shadowref::cli
