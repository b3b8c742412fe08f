// Replay of a trace (trace.h): its commands executed again, on one of shadowref's pipelines or on
// a real OpenGL through OSMesa (osmesa/, where the build has it), and the buffers each
// framebuffer ends with.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "gl/fragment_shader.h"
#include "gl/pipeline.h"
#include "trace/trace.h"

namespace shadowref::trace {

// How the trace is executed:
//  - Exact: every shader as captured, every framebuffer in its own depth format: a replay on
//    the reference or the fast pipeline must give the recorded bytes.
//  - FixedFunction: what an OpenGL 2.1 without programs can draw, in both shadowref and the GL
//    it is compared with: depth 24-bit in every framebuffer, clip coordinates rounded to float
//    (GL's vertex pipeline), and each shader evaluated once per vertex (front facing) with its
//    RGBA clamped to [0, 1] and interpolated (glColor4d with GL_SMOOTH).
enum class ReplayMode { Exact, FixedFunction };

struct ReplayResult {
  std::vector<Buffers> buffers;  // per target
};

// Runs the trace on a shadowref pipeline of `kind` (threads as makePipelineMaker's).
ReplayResult replayOnShadowref(const Trace& trace, PipelineKind kind, int threads, ReplayMode mode);

// The shaders of a trace made again from their descriptions (they own the shadow lookups they
// read); index as Trace::shaders.
class ReplayShaders {
 public:
  explicit ReplayShaders(const Trace& trace);
  ~ReplayShaders();
  const FragmentShader& operator[](size_t i) const { return *shaders_[i]; }

 private:
  struct Owned;
  std::vector<std::unique_ptr<Owned>> owned_;
  std::vector<std::unique_ptr<FragmentShader>> shaders_;
};

// A draw in the FixedFunction mode: positions rounded to float, colours of the shader at each
// vertex (RGBA in varyings 0..3, clamped to [0, 1], rounded to float); drawn with
// ColorVaryingShader, or with no colour when the draw has no shader.
std::vector<ClipVertex> fixedFunctionVertices(const DrawCommand& draw, const FragmentShader* shader);

// The triangles of a draw as clip-space corner triples (indices resolved).
void forEachTriangle(const DrawCommand& draw, const std::function<void(const glm::dvec4&, const glm::dvec4&, const glm::dvec4&)>& f);

}  // namespace shadowref::trace
