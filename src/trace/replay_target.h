// Where `shadowref replay --on` runs a trace: shadowref's reference or fast pipeline, or Mesa
// through OSMesa with the softpipe or llvmpipe driver (in a build that found OSMesa).
#pragma once

#include <optional>
#include <string>

#include "gl/pipeline.h"
#include "trace/trace_replay.h"

namespace shadowref::trace {

struct ReplayTarget {
  std::string name;      // as given: "reference", "fast", "osmesa:llvmpipe", "osmesa:softpipe"
  bool gl = false;       // a real OpenGL
  PipelineKind kind = PipelineKind::Reference;
  std::string driver;    // with gl: "llvmpipe" or "softpipe"
};

// nullopt for a name that is none of the above.
std::optional<ReplayTarget> parseReplayTarget(const std::string& name);
// Whether this build can replay on OSMesa.
bool osmesaAvailable();

// Runs the trace there. A real GL needs mode FixedFunction. Throws std::runtime_error.
ReplayResult replayOn(const Trace& trace, const ReplayTarget& target, ReplayMode mode, int threads);

}  // namespace shadowref::trace
