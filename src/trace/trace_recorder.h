// Capture (`shadowref render --capture`): a decorator around the frame's pipelines that encodes
// every command at the Pipeline boundary (gl/pipeline.h) before passing it on, and when a
// pipeline goes, the buffers its framebuffer held after its last command. The trace is held in memory and written whole
// (atomically) by finish().
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "gl/depth_compare_sampler.h"
#include "gl/pipeline.h"
#include "trace/trace.h"

namespace shadowref::trace {

class TraceRecorder {
 public:
  TraceRecorder();

  // Pipelines that record into this trace and draw through `inner`'s: give it as the frame's
  // FrameOptions::pipelines. The recorder must outlive the maker and every pipeline made.
  std::unique_ptr<PipelineMaker> wrap(const PipelineMaker& inner);

  // The trace's bytes with its end record; then writes them to `path` atomically.
  const std::vector<uint8_t>& finish();
  void write(const std::string& path);

  // Used by the recording pipelines.
  uint32_t addTarget(const Framebuffer& fb);
  void clear(uint32_t target, const ClearRequest& request);
  void draw(uint32_t target, const DrawCall& call);
  void accumulate(uint32_t target, const RenderState& state, AccumOp op, float value);
  void endPass(uint32_t target);
  void result(uint32_t target, const Buffers& buffers);

 private:
  uint32_t shaderId(const FragmentShader& shader);
  uint32_t textureId(const DepthTexture& texture);

  std::vector<uint8_t> bytes_;
  uint32_t targets_ = 0;
  uint64_t targetPixels_ = 0;  // of every framebuffer together, against ReadLimits
  bool finished_ = false;
  // The shaders encoded since the last end of a pass (a draw's shader lives until its pass ends,
  // so its address names it until then).
  std::map<const FragmentShader*, uint32_t> shaders_;
  uint32_t shaderCount_ = 0;
  // The textures encoded, by address and content hash (an address may be reused by another map).
  struct TextureKey {
    const DepthTexture* texture;
    uint64_t hash;
    int width, height;
    auto operator<=>(const TextureKey&) const = default;
  };
  std::map<TextureKey, uint32_t> textures_;
};

}  // namespace shadowref::trace
