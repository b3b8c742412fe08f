#include "trace/replay_target.h"

#include <stdexcept>

#ifdef SHADOWREF_HAVE_OSMESA
#include "trace/osmesa/osmesa_replay.h"
#endif

namespace shadowref::trace {

std::optional<ReplayTarget> parseReplayTarget(const std::string& name) {
  if (name == "reference") return ReplayTarget{name, false, PipelineKind::Reference, ""};
  if (name == "fast") return ReplayTarget{name, false, PipelineKind::Fast, ""};
  if (name == "osmesa:llvmpipe") return ReplayTarget{name, true, PipelineKind::Reference, "llvmpipe"};
  if (name == "osmesa:softpipe") return ReplayTarget{name, true, PipelineKind::Reference, "softpipe"};
  return std::nullopt;
}

bool osmesaAvailable() {
#ifdef SHADOWREF_HAVE_OSMESA
  return true;
#else
  return false;
#endif
}

ReplayResult replayOn(const Trace& trace, const ReplayTarget& target, ReplayMode mode, int threads) {
  if (!target.gl) return replayOnShadowref(trace, target.kind, threads, mode);
  if (mode != ReplayMode::FixedFunction) throw std::logic_error("a real GL replays in the fixed-function mode");
#ifdef SHADOWREF_HAVE_OSMESA
  return replayOnOsmesa(trace, target.driver);
#else
  throw std::runtime_error(target.name + ": this build has no OSMesa (install libosmesa6-dev and rebuild)");
#endif
}

}  // namespace shadowref::trace
