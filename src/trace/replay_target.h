// Where `shadowref replay --on` runs a trace: shadowref's reference or fast pipeline, or Mesa
// with the softpipe or llvmpipe driver through OSMesa (in a build that found OSMesa) or through
// EGL's surfaceless platform (in a build that found OSMesa and EGL).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "gl/pipeline.h"
#include "trace/trace_replay.h"

namespace shadowref::trace {

struct ReplayTarget {
  std::string name;      // as given: "reference", "fast", "osmesa:llvmpipe", "egl:softpipe", ...
  bool gl = false;       // a real OpenGL
  std::string api;       // with gl: "osmesa" or "egl"
  PipelineKind kind = PipelineKind::Reference;
  std::string driver;    // with gl: "llvmpipe" or "softpipe"
};

// nullopt for a name that is none of the above.
std::optional<ReplayTarget> parseReplayTarget(const std::string& name);
// Whether this build can replay on OSMesa, and on EGL.
bool osmesaAvailable();
bool eglAvailable();
// The names parseReplayTarget accepts.
const std::vector<std::string>& replayTargetNames();

// Runs the trace there. A real GL needs mode FixedFunction. Throws std::runtime_error.
ReplayResult replayOn(const Trace& trace, const ReplayTarget& target, ReplayMode mode, int threads);

}  // namespace shadowref::trace
