#include "trace/replay_target.h"

#include <stdexcept>

#ifdef SHADOWREF_HAVE_OSMESA
#include "trace/osmesa/osmesa_replay.h"
#endif
#ifdef SHADOWREF_HAVE_EGL
#include "trace/osmesa/egl_replay.h"
#endif

namespace shadowref::trace {

std::optional<ReplayTarget> parseReplayTarget(const std::string& name) {
  if (name == "reference") return ReplayTarget{name, false, "", PipelineKind::Reference, ""};
  if (name == "fast") return ReplayTarget{name, false, "", PipelineKind::Fast, ""};
  for (const char* api : {"osmesa", "egl"})
    for (const char* driver : {"llvmpipe", "softpipe"})
      if (name == std::string(api) + ":" + driver) return ReplayTarget{name, true, api, PipelineKind::Reference, driver};
  return std::nullopt;
}

const std::vector<std::string>& replayTargetNames() {
  static const std::vector<std::string> names = {"reference",       "fast",         "osmesa:llvmpipe",
                                                 "osmesa:softpipe", "egl:llvmpipe", "egl:softpipe"};
  return names;
}

bool eglAvailable() {
#ifdef SHADOWREF_HAVE_EGL
  return true;
#else
  return false;
#endif
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
  if (target.api == "egl") {
#ifdef SHADOWREF_HAVE_EGL
    return replayOnEgl(trace, target.driver);
#else
    throw std::runtime_error(target.name + ": this build has no EGL (install libegl-dev and libegl-mesa0 and rebuild)");
#endif
  }
#ifdef SHADOWREF_HAVE_OSMESA
  return replayOnOsmesa(trace, target.driver);
#else
  throw std::runtime_error(target.name + ": this build has no OSMesa (install libosmesa6-dev and rebuild)");
#endif
}

}  // namespace shadowref::trace
