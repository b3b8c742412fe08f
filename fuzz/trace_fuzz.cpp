// libFuzzer target: the input is a trace file (docs/trace-format.md), as `shadowref replay`
// reads it. A malformed one must be refused with a TraceError (its byte offset inside the input),
// never a crash, a hang or an allocation beyond the limits; a well-formed one is replayed on the
// reference pipeline in both modes and compared with its recorded buffers, with the edge
// classification and the text report, as the command does. The framebuffer limits are small (64
// pixels a side) so that a replay's work, at most the input's triangles times a framebuffer's
// pixels, stays within the fuzzer's time per input.
#include <cstdint>
#include <span>

#include "trace/trace_compare.h"
#include "trace/trace_file.h"
#include "trace/trace_replay.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace shadowref::trace;
  ReadLimits limits;
  limits.maxSide = 64;
  limits.maxPixels = 64 * 64;
  limits.maxTotalPixels = 4 * 64 * 64;
  limits.maxTargets = 8;
  Trace trace;
  try {
    trace = parseTrace(std::span<const uint8_t>(data, size), limits);
  } catch (const TraceError& e) {
    if (e.offset() > size) __builtin_trap();  // the offset must lie in the input (or at its end)
    return 0;
  }
  for (ReplayMode mode : {ReplayMode::Exact, ReplayMode::FixedFunction}) {
    const ReplayResult r = replayOnShadowref(trace, shadowref::PipelineKind::Reference, 1, mode);
    std::vector<const Buffers*> expected;
    for (const auto& b : trace.results) expected.push_back(b ? &*b : nullptr);
    std::vector<Tolerances> tolerances(trace.targets.size());
    for (uint32_t t = 0; t < tolerances.size(); ++t) {
      tolerances[t].exact = mode == ReplayMode::Exact;
      tolerances[t].colorTolerance255 = fixedFunctionColorTolerance(trace, t);
    }
    const Comparison c = compareBuffers(trace, expected, r.buffers, tolerances);
    (void)reportText(c);
  }
  return 0;
}
