// A captured frame (`shadowref render --capture`): every command its passes gave the Pipeline
// boundary (gl/pipeline.h) — clears, draws with their clip-space vertices, indices, state and
// shader, accumulation operations, ends of passes — on every framebuffer it drew into (the frame
// and its shadow maps), and the buffers each framebuffer held at the end. The file format is
// specified in docs/trace-format.md; trace_file.h reads and writes it.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "gl/clear.h"
#include "gl/accumulation.h"
#include "gl/depth_compare_sampler.h"
#include "gl/framebuffer.h"
#include "gl/render_state.h"
#include "gl/shader_description.h"
#include "gl/vertex.h"

namespace shadowref::trace {

inline constexpr char kMagic[8] = {'S', 'R', 'T', 'R', 'A', 'C', 'E', '\0'};
inline constexpr uint32_t kVersion = 1;
inline constexpr uint32_t kNoShader = 0xFFFFFFFFu;

// Record types: one byte, then the payload's length (u32), then the payload.
enum class RecordType : uint8_t {
  Target = 'T',
  Texture = 'X',
  Shader = 'S',
  Clear = 'C',
  Draw = 'D',
  Accum = 'A',
  EndPass = 'E',
  Result = 'R',
  End = 'Z',
};

// A framebuffer the frame drew into: 0 is the frame, the others its shadow maps.
struct Target {
  int width = 0, height = 0;
  DepthFormat depthFormat = DepthFormat::Float32;
};

struct Shader {
  ShaderDescription description;  // its DepthTexture pointers point into Trace::textures
};

struct ClearCommand {
  ClearRequest request;
};

struct DrawCommand {
  RenderState state;
  uint32_t tag = 0;
  uint32_t shader = kNoShader;  // index into Trace::shaders
  int varyingCount = 0;         // varyings stored per vertex (the rest are 0)
  std::vector<ClipVertex> vertices;
  std::vector<uint32_t> indices;  // empty: vertices [3i, 3i+2] are triangle i
};

struct AccumCommand {
  RenderState state;
  AccumOp op = AccumOp::Accum;
  float value = 0.0f;
};

struct EndPassCommand {};

struct Command {
  uint32_t target = 0;
  uint64_t offset = 0;  // of the record in the file, for messages
  std::variant<ClearCommand, DrawCommand, AccumCommand, EndPassCommand> what;
};

// A framebuffer's buffers at the end of the frame; an absent buffer is empty.
struct Buffers {
  int width = 0, height = 0;
  DepthFormat depthFormat = DepthFormat::Float32;
  std::vector<glm::vec4> color;
  std::vector<uint32_t> depth;  // codes of depthFormat (gl/framebuffer.h)
  std::vector<uint8_t> stencil;
  std::vector<glm::vec4> accum;
};

struct Trace {
  std::vector<Target> targets;
  std::vector<std::unique_ptr<DepthTexture>> textures;  // stable addresses: shaders point at them
  std::vector<Shader> shaders;
  std::vector<Command> commands;
  std::vector<std::optional<Buffers>> results;  // per target, when recorded
};

// Buffers of a framebuffer as it stands.
Buffers buffersOf(const Framebuffer& fb);

}  // namespace shadowref::trace
