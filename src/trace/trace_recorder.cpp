#include "trace/trace_recorder.h"

#include <optional>
#include <stdexcept>

#include "gl/shader_description.h"
#include "image/atomic_write.h"
#include "trace/trace_file.h"

namespace shadowref::trace {

namespace {

class RecordingPipeline final : public Pipeline {
 public:
  RecordingPipeline(std::unique_ptr<Pipeline> inner, TraceRecorder& recorder, uint32_t target)
      : inner_(std::move(inner)), recorder_(recorder), target_(target) {}
  ~RecordingPipeline() override {
    // The buffers as the last command left them: taken when the framebuffer was handed out after
    // it (whoever takes it may move a buffer out, as a shadow map's depth becomes its texture),
    // else now. A destructor must not throw: a frame that failed (the exception is on its way)
    // records no result, and its trace is not written.
    try {
      if (!snapshot_ || dirty_) snapshot_ = buffersOf(inner_->framebuffer());
      recorder_.result(target_, *snapshot_);
    } catch (...) {
    }
  }

  PipelineKind kind() const override { return inner_->kind(); }
  int threads() const override { return inner_->threads(); }
  void clear(const ClearRequest& request) override {
    dirty_ = true;
    recorder_.clear(target_, request);
    inner_->clear(request);
  }
  void draw(const DrawCall& call) override {
    dirty_ = true;
    recorder_.draw(target_, call);
    inner_->draw(call);
  }
  void accumulate(const RenderState& state, AccumOp op, float value) override {
    dirty_ = true;
    recorder_.accumulate(target_, state, op, value);
    inner_->accumulate(state, op, value);
  }
  void endPass() override {
    recorder_.endPass(target_);
    inner_->endPass();
  }
  Framebuffer& framebuffer() override {
    recorder_.endPass(target_);
    Framebuffer& fb = inner_->framebuffer();
    if (dirty_) snapshot_ = buffersOf(fb);
    dirty_ = false;
    return fb;
  }
  const RasterStats& stats() const override { return inner_->stats(); }
  void resetStats() override { inner_->resetStats(); }
  void watchPixel(int x, int y, FragmentObserver* observer) override { inner_->watchPixel(x, y, observer); }
  void forEachIndependent(int count, const std::function<void(int)>& task) override {
    inner_->forEachIndependent(count, task);
  }
  std::unique_ptr<Pipeline> forFramebuffer(Framebuffer& fb) const override {
    const uint32_t target = recorder_.addTarget(fb);
    return std::make_unique<RecordingPipeline>(inner_->forFramebuffer(fb), recorder_, target);
  }

 private:
  std::unique_ptr<Pipeline> inner_;
  TraceRecorder& recorder_;
  uint32_t target_;
  std::optional<Buffers> snapshot_;  // the buffers when last handed out
  bool dirty_ = false;               // a command since then
};

class RecordingMaker final : public PipelineMaker {
 public:
  RecordingMaker(const PipelineMaker& inner, TraceRecorder& recorder) : inner_(inner), recorder_(recorder) {}
  PipelineKind kind() const override { return inner_.kind(); }
  int threads() const override { return inner_.threads(); }
  std::unique_ptr<Pipeline> make(Framebuffer& fb) const override {
    const uint32_t target = recorder_.addTarget(fb);
    return std::make_unique<RecordingPipeline>(inner_.make(fb), recorder_, target);
  }

 private:
  const PipelineMaker& inner_;
  TraceRecorder& recorder_;
};

// FNV-1a over the texels: tells a map at a reused address from the one encoded there before.
uint64_t hashTexture(const DepthTexture& t) {
  uint64_t h = 1469598103934665603ull;
  for (uint32_t v : t.bits) {
    h ^= v;
    h *= 1099511628211ull;
  }
  return h;
}

}  // namespace

TraceRecorder::TraceRecorder() { Encoder(bytes_).header(); }

std::unique_ptr<PipelineMaker> TraceRecorder::wrap(const PipelineMaker& inner) {
  return std::make_unique<RecordingMaker>(inner, *this);
}

uint32_t TraceRecorder::addTarget(const Framebuffer& fb) {
  Encoder e(bytes_);
  const size_t r = e.beginRecord(RecordType::Target);
  e.i32(fb.width());
  e.i32(fb.height());
  e.u8(uint8_t(fb.depthCodec().format));
  e.endRecord(r);
  targetPixels_ += uint64_t(fb.width()) * uint64_t(fb.height());
  return targets_++;
}

void TraceRecorder::clear(uint32_t target, const ClearRequest& q) {
  Encoder e(bytes_);
  const size_t r = e.beginRecord(RecordType::Clear);
  e.u32(target);
  e.state(q.state);
  e.u8(uint8_t((q.color ? 1 : 0) | (q.depth ? 2 : 0) | (q.stencil ? 4 : 0) | (q.accum ? 8 : 0)));
  const glm::vec4 colour = q.color.value_or(glm::vec4(0.0f)), accum = q.accum.value_or(glm::vec4(0.0f));
  for (int i = 0; i < 4; ++i) e.f32(colour[i]);
  e.f64(q.depth.value_or(1.0));
  e.i32(q.stencil.value_or(0));
  for (int i = 0; i < 4; ++i) e.f32(accum[i]);
  e.endRecord(r);
}

uint32_t TraceRecorder::textureId(const DepthTexture& texture) {
  const TextureKey key{&texture, hashTexture(texture), texture.width, texture.height};
  if (const auto it = textures_.find(key); it != textures_.end()) return it->second;
  const uint32_t id = uint32_t(textures_.size());
  Encoder e(bytes_);
  const size_t r = e.beginRecord(RecordType::Texture);
  e.u32(id);
  e.i32(texture.width);
  e.i32(texture.height);
  for (uint32_t v : texture.bits) e.u32(v);
  e.endRecord(r);
  textures_.emplace(key, id);
  return id;
}

uint32_t TraceRecorder::shaderId(const FragmentShader& shader) {
  if (const auto it = shaders_.find(&shader); it != shaders_.end()) return it->second;
  ShaderDescription d;
  if (!shader.describe(d))
    throw std::runtime_error("--capture: a draw uses a shader that a trace cannot hold (trace format " +
                             std::to_string(kVersion) + " holds constant, colour, Gouraud, Phong and shadow-mapped shaders)");
  std::vector<uint32_t> textureIds;
  for (const LightShadowDescription& s : d.shadows)
    for (const ShadowMapDescription& m : s.maps) {
      if (!m.texture) throw std::runtime_error("--capture: a shadow map without a texture");
      textureIds.push_back(textureId(*m.texture));
    }
  const uint32_t id = shaderCount_++;
  Encoder e(bytes_);
  const size_t r = e.beginRecord(RecordType::Shader);
  e.u32(id);
  e.shader(d, textureIds);
  e.endRecord(r);
  shaders_.emplace(&shader, id);
  return id;
}

void TraceRecorder::draw(uint32_t target, const DrawCall& call) {
  const uint32_t shader = call.shader ? shaderId(*call.shader) : kNoShader;
  const int varyings = call.shader ? call.shader->varyingCount() : 0;
  Encoder e(bytes_);
  const size_t r = e.beginRecord(RecordType::Draw);
  e.u32(target);
  e.state(*call.state);
  e.u32(call.tag);
  e.u32(shader);
  e.u8(uint8_t(varyings));
  e.u32(uint32_t(call.vertices.size()));
  for (const ClipVertex& v : call.vertices) {
    for (int i = 0; i < 4; ++i) e.f64(v.position[i]);
    for (int i = 0; i < varyings; ++i) e.f64(v.varyings[size_t(i)]);
  }
  e.u32(uint32_t(call.indices.size()));
  for (uint32_t i : call.indices) e.u32(i);
  e.endRecord(r);
}

void TraceRecorder::accumulate(uint32_t target, const RenderState& state, AccumOp op, float value) {
  Encoder e(bytes_);
  const size_t r = e.beginRecord(RecordType::Accum);
  e.u32(target);
  e.state(state);
  e.u8(uint8_t(op));
  e.f32(value);
  e.endRecord(r);
  shaders_.clear();  // accumulate ends the pass
}

void TraceRecorder::endPass(uint32_t target) {
  Encoder e(bytes_);
  const size_t r = e.beginRecord(RecordType::EndPass);
  e.u32(target);
  e.endRecord(r);
  shaders_.clear();
}

void TraceRecorder::result(uint32_t target, const Buffers& buffers) {
  Encoder e(bytes_);
  const size_t r = e.beginRecord(RecordType::Result);
  e.buffers(target, buffers);
  e.endRecord(r);
  shaders_.clear();
}

const std::vector<uint8_t>& TraceRecorder::finish() {
  if (!finished_) {
    Encoder e(bytes_);
    e.endRecord(e.beginRecord(RecordType::End));
    finished_ = true;
  }
  return bytes_;
}

void TraceRecorder::write(const std::string& path) {
  // What capture writes, replay must read: a frame beyond the reader's limits is refused here,
  // before a file exists, rather than written and refused by `replay`.
  const ReadLimits limits;
  if (targets_ > limits.maxTargets)
    throw std::runtime_error("cannot capture '" + path + "': the frame drew into " + std::to_string(targets_) +
                             " framebuffers, a trace holds at most " + std::to_string(limits.maxTargets));
  if (targetPixels_ > limits.maxTotalPixels)
    throw std::runtime_error("cannot capture '" + path + "': the frame's framebuffers have " +
                             std::to_string(targetPixels_) + " pixels together, a trace holds at most " +
                             std::to_string(limits.maxTotalPixels));
  const std::vector<uint8_t>& bytes = finish();
  writeFileAtomically(path, [&](const TempFile& temp) { writeAllAt(temp.fd, bytes.data(), bytes.size(), 0); });
}

}  // namespace shadowref::trace
