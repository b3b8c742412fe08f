#include "trace/trace_file.h"

#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>

namespace shadowref::trace {

// ---- writing ----

void Encoder::u32(uint32_t v) {
  for (int i = 0; i < 4; ++i) out_.push_back(uint8_t(v >> (8 * i)));
}
void Encoder::u64(uint64_t v) {
  for (int i = 0; i < 8; ++i) out_.push_back(uint8_t(v >> (8 * i)));
}
void Encoder::f32(float v) { u32(std::bit_cast<uint32_t>(v)); }
void Encoder::f64(double v) { u64(std::bit_cast<uint64_t>(v)); }
void Encoder::bytes(const void* data, size_t size) {
  const auto* p = static_cast<const uint8_t*>(data);
  out_.insert(out_.end(), p, p + size);
}

size_t Encoder::beginRecord(RecordType type) {
  u8(uint8_t(type));
  const size_t start = out_.size();
  u32(0);
  return start;
}

void Encoder::endRecord(size_t start) {
  const uint64_t length = out_.size() - start - 4;
  if (length > UINT32_MAX) throw std::runtime_error("a trace record is larger than 4 GiB");
  for (int i = 0; i < 4; ++i) out_[start + size_t(i)] = uint8_t(length >> (8 * i));
}

void Encoder::header() {
  bytes(kMagic, sizeof kMagic);
  u32(kVersion);
}

void Encoder::state(const RenderState& s) {
  i32(s.viewport.x);
  i32(s.viewport.y);
  i32(s.viewport.width);
  i32(s.viewport.height);
  f64(s.viewport.nearVal);
  f64(s.viewport.farVal);
  u8(s.scissorTest);
  i32(s.scissor.x);
  i32(s.scissor.y);
  i32(s.scissor.width);
  i32(s.scissor.height);
  u8(uint8_t(s.cull));
  u8(uint8_t(s.frontFace));
  u8(s.depthTest);
  u8(uint8_t(s.depthFunc));
  u8(s.depthWrite);
  u8(s.depthClamp);
  u8(s.clipFar);
  u8(s.polygonOffset.enabled);
  f64(s.polygonOffset.factor);
  f64(s.polygonOffset.units);
  u8(s.stencilTest);
  for (const StencilFaceState& f : s.stencil) {
    u8(uint8_t(f.func));
    i32(f.ref);
    u8(f.mask);
    u8(f.writeMask);
    u8(uint8_t(f.sfail));
    u8(uint8_t(f.dpfail));
    u8(uint8_t(f.dppass));
  }
  u8(s.blend.enabled);
  u8(uint8_t(s.blend.src));
  u8(uint8_t(s.blend.dst));
  for (bool m : s.colorMask) u8(m);
}

namespace {

void vec3(Encoder& e, const glm::dvec3& v) {
  for (int i = 0; i < 3; ++i) e.f64(v[i]);
}
void vec4(Encoder& e, const glm::dvec4& v) {
  for (int i = 0; i < 4; ++i) e.f64(v[i]);
}
void mat4(Encoder& e, const glm::dmat4& m) {
  for (int c = 0; c < 4; ++c) vec4(e, m[c]);
}

void setup(Encoder& e, const LightingSetup& s) {
  vec3(e, s.material.ambient);
  vec3(e, s.material.diffuse);
  vec3(e, s.material.specular);
  vec3(e, s.material.emission);
  e.f64(s.material.shininess);
  e.u8(s.material.blinn);
  vec3(e, s.globalAmbient);
  e.u8(s.includeAmbient);
  vec3(e, s.eye);
  e.u32(uint32_t(s.lights.size()));
  for (const PhongLight& l : s.lights) {
    vec4(e, l.position);
    vec3(e, l.diffuse);
    vec3(e, l.specular);
    vec3(e, l.spotDirection);
    e.f64(l.spotCosCutoff);
    e.f64(l.spotExponent);
    vec3(e, l.attenuation);
  }
}

}  // namespace

void Encoder::shader(const ShaderDescription& d, const std::vector<uint32_t>& textureIds) {
  u8(uint8_t(d.kind));
  if (d.kind == ShaderKind::Constant) vec4(*this, d.color);
  if (d.kind == ShaderKind::PerPixelLighting || d.kind == ShaderKind::ShadowMapped) setup(*this, d.setup);
  if (d.kind != ShaderKind::ShadowMapped && d.kind != ShaderKind::ShadowMappedGouraud) return;
  size_t next = 0;
  u32(uint32_t(d.shadows.size()));
  for (const LightShadowDescription& s : d.shadows) {
    u8(s.cube);
    vec3(*this, s.lightPosition);
    u8(s.trapezoidal);
    mat4(*this, s.lightView);
    mat4(*this, s.lightProjection);
    u32(uint32_t(s.maps.size()));
    for (const ShadowMapDescription& m : s.maps) {
      mat4(*this, m.textureMatrix);
      u32(textureIds.at(next++));
      u8(uint8_t(m.func));
      f64(m.failValue);
      i32(m.pcf);
      f64(m.constantBias);
      u8(uint8_t((m.outsideLit ? 1u : 0u) | (unsigned(m.receiverPlaneBias) << 1)));  // the map flags
    }
  }
}

void Encoder::buffers(uint32_t target, const Buffers& b) {
  u32(target);
  const uint8_t present = uint8_t((b.color.empty() ? 0 : 1) | (b.depth.empty() ? 0 : 2) | (b.stencil.empty() ? 0 : 4) |
                                  (b.accum.empty() ? 0 : 8));
  u8(present);
  for (const glm::vec4& c : b.color)
    for (int i = 0; i < 4; ++i) f32(c[i]);
  for (uint32_t d : b.depth) u32(d);
  bytes(b.stencil.data(), b.stencil.size());
  for (const glm::vec4& c : b.accum)
    for (int i = 0; i < 4; ++i) f32(c[i]);
}

Buffers buffersOf(const Framebuffer& fb) {
  Buffers b;
  b.width = fb.width();
  b.height = fb.height();
  b.depthFormat = fb.depthCodec().format;
  if (fb.hasColor()) b.color.assign(fb.color().begin(), fb.color().end());
  if (fb.hasDepth()) b.depth.assign(fb.depthCodes().begin(), fb.depthCodes().end());
  if (fb.hasStencil()) b.stencil.assign(fb.stencil().begin(), fb.stencil().end());
  if (fb.hasAccum()) b.accum.assign(fb.accum().begin(), fb.accum().end());
  return b;
}

// ---- reading ----

namespace {

// Reads values from [at, end) of the file; every read checks that its bytes are there, and
// every error names the offset of the value that is wrong.
class Cursor {
 public:
  Cursor(const uint8_t* data, uint64_t at, uint64_t end) : data_(data), at_(at), end_(end) {}
  uint64_t at() const { return at_; }
  uint64_t remaining() const { return end_ - at_; }
  [[noreturn]] void fail(const std::string& message) const { throw TraceError(at_, message); }
  [[noreturn]] void failAt(uint64_t offset, const std::string& message) const { throw TraceError(offset, message); }

  void need(uint64_t n, const char* what) const {
    if (n > remaining())
      fail(std::string("truncated: ") + what + " needs " + std::to_string(n) + " bytes, " +
           std::to_string(remaining()) + " left");
  }
  uint8_t u8(const char* what) {
    need(1, what);
    return data_[at_++];
  }
  uint32_t u32(const char* what) {
    need(4, what);
    uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= uint32_t(data_[at_ + uint64_t(i)]) << (8 * i);
    at_ += 4;
    return v;
  }
  int32_t i32(const char* what) { return int32_t(u32(what)); }
  uint64_t u64(const char* what) {
    need(8, what);
    uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v |= uint64_t(data_[at_ + uint64_t(i)]) << (8 * i);
    at_ += 8;
    return v;
  }
  float f32(const char* what) {
    const uint64_t start = at_;
    const float v = std::bit_cast<float>(u32(what));
    if (!std::isfinite(v)) failAt(start, std::string(what) + " is not a finite number");
    return v;
  }
  double f64(const char* what) {
    const uint64_t start = at_;
    const double v = std::bit_cast<double>(u64(what));
    if (!std::isfinite(v)) failAt(start, std::string(what) + " is not a finite number");
    return v;
  }
  double f64In(const char* what, double lo, double hi) {
    const uint64_t start = at_;
    const double v = f64(what);
    if (v < lo || v > hi)
      failAt(start, std::string(what) + " " + std::to_string(v) + " is outside [" + std::to_string(lo) + ", " +
                        std::to_string(hi) + "]");
    return v;
  }
  bool flag(const char* what) {
    const uint64_t start = at_;
    const uint8_t v = u8(what);
    if (v > 1) failAt(start, std::string(what) + " is " + std::to_string(v) + ", expected 0 or 1");
    return v == 1;
  }
  template <class E>
  E enumIn(const char* what, int count) {
    const uint64_t start = at_;
    const uint8_t v = u8(what);
    if (v >= count)
      failAt(start, std::string(what) + " is " + std::to_string(v) + ", expected 0 to " + std::to_string(count - 1));
    return E(v);
  }
  int32_t intIn(const char* what, int64_t lo, int64_t hi) {
    const uint64_t start = at_;
    const int32_t v = i32(what);
    if (v < lo || v > hi)
      failAt(start, std::string(what) + " " + std::to_string(v) + " is outside [" + std::to_string(lo) + ", " +
                        std::to_string(hi) + "]");
    return v;
  }
  // A count of elements of `size` bytes each that follow: at most what the bytes left can hold.
  uint32_t count(const char* what, uint64_t size) {
    const uint64_t start = at_;
    const uint32_t n = u32(what);
    if (uint64_t(n) * size > remaining())
      failAt(start, std::string(what) + " " + std::to_string(n) + " needs " + std::to_string(uint64_t(n) * size) +
                        " bytes, the record has " + std::to_string(remaining()) + " left");
    return n;
  }

 private:
  const uint8_t* data_;
  uint64_t at_, end_;
};

// Viewport and scissor coordinates: within a few times the largest framebuffer (GL clamps the
// viewport to its maximum dimensions; nothing real lies beyond).
constexpr int64_t kMaxCoordinate = 1 << 20;

RenderState readState(Cursor& c) {
  RenderState s;
  s.viewport.x = c.intIn("viewport x", -kMaxCoordinate, kMaxCoordinate);
  s.viewport.y = c.intIn("viewport y", -kMaxCoordinate, kMaxCoordinate);
  s.viewport.width = c.intIn("viewport width", 0, kMaxCoordinate);
  s.viewport.height = c.intIn("viewport height", 0, kMaxCoordinate);
  s.viewport.nearVal = c.f64In("depth range near", 0.0, 1.0);
  s.viewport.farVal = c.f64In("depth range far", 0.0, 1.0);
  s.scissorTest = c.flag("scissor test");
  s.scissor.x = c.intIn("scissor x", -kMaxCoordinate, kMaxCoordinate);
  s.scissor.y = c.intIn("scissor y", -kMaxCoordinate, kMaxCoordinate);
  s.scissor.width = c.intIn("scissor width", 0, kMaxCoordinate);
  s.scissor.height = c.intIn("scissor height", 0, kMaxCoordinate);
  s.cull = c.enumIn<CullMode>("cull mode", 4);
  s.frontFace = c.enumIn<FrontFace>("front face", 2);
  s.depthTest = c.flag("depth test");
  s.depthFunc = c.enumIn<CompareFunc>("depth func", 8);
  s.depthWrite = c.flag("depth write");
  s.depthClamp = c.flag("depth clamp");
  s.clipFar = c.flag("far clipping");
  s.polygonOffset.enabled = c.flag("polygon offset");
  s.polygonOffset.factor = c.f64In("polygon offset factor", -1e6, 1e6);
  s.polygonOffset.units = c.f64In("polygon offset units", -1e9, 1e9);
  s.stencilTest = c.flag("stencil test");
  for (StencilFaceState& f : s.stencil) {
    f.func = c.enumIn<CompareFunc>("stencil func", 8);
    f.ref = c.i32("stencil ref");
    f.mask = c.u8("stencil mask");
    f.writeMask = c.u8("stencil write mask");
    f.sfail = c.enumIn<StencilOp>("stencil op sfail", 8);
    f.dpfail = c.enumIn<StencilOp>("stencil op dpfail", 8);
    f.dppass = c.enumIn<StencilOp>("stencil op dppass", 8);
  }
  s.blend.enabled = c.flag("blend");
  s.blend.src = c.enumIn<BlendFactor>("blend source factor", 10);
  s.blend.dst = c.enumIn<BlendFactor>("blend destination factor", 10);
  for (bool& m : s.colorMask) m = c.flag("colour mask");
  return s;
}

// Lighting values: finite and within what a scene may hold (scene/resource_limits.h).
glm::dvec3 vec3(Cursor& c, const char* what) {
  glm::dvec3 v;
  for (int i = 0; i < 3; ++i) v[i] = c.f64In(what, -kMaxWorldMagnitude, kMaxWorldMagnitude);
  return v;
}
glm::dvec4 vec4(Cursor& c, const char* what) {
  glm::dvec4 v;
  for (int i = 0; i < 4; ++i) v[i] = c.f64In(what, -kMaxWorldMagnitude, kMaxWorldMagnitude);
  return v;
}
glm::dmat4 mat4(Cursor& c, const char* what) {
  glm::dmat4 m;
  for (int i = 0; i < 4; ++i) m[i] = vec4(c, what);
  return m;
}

constexpr size_t kLightBytes = 8 * (4 + 3 + 3 + 3 + 1 + 1 + 3);
// The largest PCF kernel a trace may ask for (k x k taps per lookup).
constexpr int kMaxPcf = 31;

LightingSetup readSetup(Cursor& c) {
  LightingSetup s;
  s.material.ambient = vec3(c, "material ambient");
  s.material.diffuse = vec3(c, "material diffuse");
  s.material.specular = vec3(c, "material specular");
  s.material.emission = vec3(c, "material emission");
  s.material.shininess = c.f64In("shininess", 0.0, 1e6);
  s.material.blinn = c.flag("Blinn-Phong");
  s.globalAmbient = vec3(c, "global ambient");
  s.includeAmbient = c.flag("include ambient");
  s.eye = vec3(c, "eye");
  const uint32_t n = c.count("light count", kLightBytes);
  for (uint32_t i = 0; i < n; ++i) {
    PhongLight l;
    l.position = vec4(c, "light position");
    l.diffuse = vec3(c, "light diffuse");
    l.specular = vec3(c, "light specular");
    l.spotDirection = vec3(c, "spot direction");
    l.spotCosCutoff = c.f64In("spot cutoff cosine", -1.0, 1.0);
    l.spotExponent = c.f64In("spot exponent", 0.0, 1e6);
    l.attenuation = vec3(c, "attenuation");
    s.lights.push_back(l);
  }
  return s;
}

class Parser {
 public:
  Parser(std::span<const uint8_t> bytes, const ReadLimits& limits) : bytes_(bytes), limits_(limits) {}

  Trace parse() {
    Cursor head(bytes_.data(), 0, bytes_.size());
    head.need(sizeof kMagic, "the header");
    if (std::memcmp(bytes_.data(), kMagic, sizeof kMagic) != 0) head.fail("not a shadowref trace (no SRTRACE header)");
    Cursor version(bytes_.data(), sizeof kMagic, bytes_.size());
    const uint32_t v = version.u32("the format version");
    if (v != kVersion)
      version.failAt(sizeof kMagic, "format version " + std::to_string(v) + ", this build reads version " +
                                        std::to_string(kVersion));
    uint64_t at = version.at();
    bool ended = false;
    while (at < bytes_.size()) {
      if (ended) throw TraceError(at, "bytes after the end record");
      Cursor frame(bytes_.data(), at, bytes_.size());
      const uint8_t type = frame.u8("a record type");
      const uint32_t length = frame.u32("a record length");
      if (length > frame.remaining())
        frame.failAt(at + 1, "truncated: the record's length is " + std::to_string(length) + " bytes, " +
                                 std::to_string(frame.remaining()) + " left in the file");
      Cursor c(bytes_.data(), frame.at(), frame.at() + length);
      record(at, type, c);
      if (c.remaining() != 0) c.fail(std::to_string(c.remaining()) + " unread bytes at the end of the record");
      ended = type == uint8_t(RecordType::End);
      at = frame.at() + length;
    }
    if (!ended) throw TraceError(bytes_.size(), "truncated: the trace has no end record");
    return std::move(trace_);
  }

 private:
  void record(uint64_t offset, uint8_t type, Cursor& c) {
    switch (RecordType(type)) {
      case RecordType::Target: return target(c);
      case RecordType::Texture: return texture(c);
      case RecordType::Shader: return shader(c);
      case RecordType::Clear: return clear(offset, c);
      case RecordType::Draw: return draw(offset, c);
      case RecordType::Accum: return accum(offset, c);
      case RecordType::EndPass: {
        const uint32_t t = targetIndex(c);
        trace_.commands.push_back({t, offset, EndPassCommand{}});
        return;
      }
      case RecordType::Result: return result(c);
      case RecordType::End: return;
    }
    throw TraceError(offset, "unknown record type " + std::to_string(type));
  }

  void target(Cursor& c) {
    const uint64_t start = c.at();
    if (trace_.targets.size() >= limits_.maxTargets)
      c.fail("more than " + std::to_string(limits_.maxTargets) + " framebuffers");
    Target t;
    t.width = c.intIn("framebuffer width", 1, limits_.maxSide);
    t.height = c.intIn("framebuffer height", 1, limits_.maxSide);
    t.depthFormat = c.enumIn<DepthFormat>("depth format", 2);
    const uint64_t pixels = uint64_t(t.width) * uint64_t(t.height);
    if (pixels > limits_.maxPixels)
      c.failAt(start, "framebuffer " + std::to_string(t.width) + "x" + std::to_string(t.height) + " has more than " +
                          std::to_string(limits_.maxPixels) + " pixels");
    totalPixels_ += pixels;
    if (totalPixels_ > limits_.maxTotalPixels)
      c.failAt(start, "the framebuffers have more than " + std::to_string(limits_.maxTotalPixels) + " pixels together");
    trace_.targets.push_back(t);
    trace_.results.emplace_back();
  }

  uint32_t targetIndex(Cursor& c) {
    const uint64_t start = c.at();
    const uint32_t t = c.u32("framebuffer index");
    if (t >= trace_.targets.size())
      c.failAt(start, "framebuffer " + std::to_string(t) + " is not declared (" + std::to_string(trace_.targets.size()) +
                          " so far)");
    return t;
  }

  void texture(Cursor& c) {
    const uint64_t start = c.at();
    const uint32_t id = c.u32("texture id");
    if (id != trace_.textures.size())
      c.failAt(start, "texture id " + std::to_string(id) + ", expected " + std::to_string(trace_.textures.size()));
    const int w = c.intIn("texture width", 1, limits_.maxSide);
    const int h = c.intIn("texture height", 1, limits_.maxSide);
    const uint64_t texels = uint64_t(w) * uint64_t(h);
    if (texels > limits_.maxPixels) c.failAt(start, "texture has more than " + std::to_string(limits_.maxPixels) + " texels");
    c.need(texels * 4, "the texels");
    auto tex = std::make_unique<DepthTexture>(DepthTexture::filled(w, h, 0.0f));
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const uint64_t at = c.at();
        const float d = std::bit_cast<float>(c.u32("a texel"));
        if (!(d >= 0.0f && d <= 1.0f)) c.failAt(at, "texel depth " + std::to_string(d) + " is outside [0, 1]");
        tex->set(x, y, d);
      }
    trace_.textures.push_back(std::move(tex));
  }

  const DepthTexture* textureRef(Cursor& c) {
    const uint64_t start = c.at();
    const uint32_t id = c.u32("texture id");
    if (id >= trace_.textures.size())
      c.failAt(start, "texture " + std::to_string(id) + " is not defined (" + std::to_string(trace_.textures.size()) +
                          " so far)");
    return trace_.textures[id].get();
  }

  void shader(Cursor& c) {
    const uint64_t start = c.at();
    const uint32_t id = c.u32("shader id");
    if (id != trace_.shaders.size())
      c.failAt(start, "shader id " + std::to_string(id) + ", expected " + std::to_string(trace_.shaders.size()));
    Shader s;
    ShaderDescription& d = s.description;
    const uint64_t kindAt = c.at();
    const uint8_t kind = c.u8("shader kind");
    if (kind < 1 || kind > 6) c.failAt(kindAt, "shader kind " + std::to_string(kind) + ", expected 1 to 6");
    d.kind = ShaderKind(kind);
    if (d.kind == ShaderKind::Constant)
      for (int i = 0; i < 4; ++i) d.color[i] = c.f64In("constant colour", -1e6, 1e6);
    if (d.kind == ShaderKind::PerPixelLighting || d.kind == ShaderKind::ShadowMapped) d.setup = readSetup(c);
    if (d.kind == ShaderKind::ShadowMapped || d.kind == ShaderKind::ShadowMappedGouraud) {
      const uint64_t countAt = c.at();
      const uint32_t n = c.count("shadow count", 1 + 24 + 1 + 256 + 4);
      if (d.kind == ShaderKind::ShadowMappedGouraud && n > 4)
        c.failAt(countAt, "a shadow-mapped Gouraud shader takes at most 4 lights, not " + std::to_string(n));
      for (uint32_t i = 0; i < n; ++i) {
        LightShadowDescription l;
        l.cube = c.flag("cube map");
        l.lightPosition = vec3(c, "light position");
        l.trapezoidal = c.flag("trapezoidal");
        l.lightView = mat4(c, "light view matrix");
        l.lightProjection = mat4(c, "light projection matrix");
        const uint64_t mapsAt = c.at();
        const uint32_t maps = c.count("map count", 128 + 4 + 1 + 8 + 4 + 8 + 1);
        if (maps != (l.cube ? 6u : 1u))
          c.failAt(mapsAt, std::to_string(maps) + " maps for a " + (l.cube ? "cube" : "single") + " shadow, expected " +
                               (l.cube ? "6" : "1"));
        for (uint32_t m = 0; m < maps; ++m) {
          ShadowMapDescription map;
          map.textureMatrix = mat4(c, "texture matrix");
          map.texture = textureRef(c);
          map.func = c.enumIn<CompareFunc>("compare func", 8);
          map.failValue = c.f64In("compare-fail value", 0.0, 1.0);
          map.pcf = c.intIn("PCF kernel", 1, kMaxPcf);
          map.constantBias = c.f64In("constant bias", -1.0, 1.0);
          const uint64_t flagsAt = c.at();
          const uint8_t flags = c.u8("map flags");
          if (flags > 5) c.failAt(flagsAt, "map flags are " + std::to_string(flags) + ", expected 0 to 5");
          map.outsideLit = (flags & 1u) != 0;
          map.receiverPlaneBias = uint8_t(flags >> 1);
          l.maps.push_back(map);
        }
        d.shadows.push_back(std::move(l));
      }
    }
    trace_.shaders.push_back(std::move(s));
  }

  void clear(uint64_t offset, Cursor& c) {
    const uint32_t t = targetIndex(c);
    ClearCommand cmd;
    cmd.request.state = readState(c);
    const uint64_t flagsAt = c.at();
    const uint8_t flags = c.u8("cleared buffers");
    if (flags > 15) c.failAt(flagsAt, "cleared buffers " + std::to_string(flags) + ", expected a mask of 4 bits");
    glm::vec4 colour, accum;
    for (int i = 0; i < 4; ++i) colour[i] = c.f32("clear colour");
    const double depth = c.f64In("clear depth", 0.0, 1.0);
    const int stencil = c.i32("clear stencil");
    for (int i = 0; i < 4; ++i) accum[i] = c.f32("clear accumulation value");
    if (flags & 1) cmd.request.color = colour;
    if (flags & 2) cmd.request.depth = depth;
    if (flags & 4) cmd.request.stencil = stencil;
    if (flags & 8) cmd.request.accum = accum;
    trace_.commands.push_back({t, offset, std::move(cmd)});
  }

  void draw(uint64_t offset, Cursor& c) {
    const uint32_t t = targetIndex(c);
    DrawCommand d;
    d.state = readState(c);
    d.tag = c.u32("draw tag");
    const uint64_t shaderAt = c.at();
    d.shader = c.u32("shader id");
    if (d.shader != kNoShader && d.shader >= trace_.shaders.size())
      c.failAt(shaderAt, "shader " + std::to_string(d.shader) + " is not defined (" +
                             std::to_string(trace_.shaders.size()) + " so far)");
    const uint64_t varyingsAt = c.at();
    d.varyingCount = c.u8("varying count");
    if (d.varyingCount > kMaxVaryings)
      c.failAt(varyingsAt, "varying count " + std::to_string(d.varyingCount) + ", at most " + std::to_string(kMaxVaryings));
    if (d.shader != kNoShader) {
      const int needs = varyingsOf(trace_.shaders[d.shader].description);
      if (d.varyingCount < needs)
        c.failAt(varyingsAt, "the draw gives " + std::to_string(d.varyingCount) + " varyings, its shader reads " +
                                 std::to_string(needs));
    }
    const uint32_t n = c.count("vertex count", 8 * uint64_t(4 + d.varyingCount));
    d.vertices.resize(n);
    for (ClipVertex& v : d.vertices) {
      for (int i = 0; i < 4; ++i) v.position[i] = c.f64In("a clip coordinate", -1e300, 1e300);
      for (int i = 0; i < d.varyingCount; ++i) v.varyings[size_t(i)] = c.f64In("a varying", -1e300, 1e300);
    }
    const uint64_t indicesAt = c.at();
    const uint32_t k = c.count("index count", 4);
    if (k % 3 != 0) c.failAt(indicesAt, "index count " + std::to_string(k) + " is not a multiple of 3");
    if (k == 0 && n % 3 != 0) c.failAt(indicesAt, "no indices and a vertex count " + std::to_string(n) + " that is not a multiple of 3");
    d.indices.resize(k);
    for (uint32_t& i : d.indices) {
      const uint64_t at = c.at();
      i = c.u32("an index");
      if (i >= n) c.failAt(at, "index " + std::to_string(i) + " of a draw of " + std::to_string(n) + " vertices");
    }
    trace_.commands.push_back({t, offset, std::move(d)});
  }

  static int varyingsOf(const ShaderDescription& d) {
    switch (d.kind) {
      case ShaderKind::Constant: return 0;
      case ShaderKind::ColorVarying: return 4;
      case ShaderKind::Gouraud: return 3;
      case ShaderKind::PerPixelLighting:
      case ShaderKind::ShadowMapped: return 6;
      case ShaderKind::ShadowMappedGouraud: return 3 + 3 * int(d.shadows.size());
    }
    return 0;
  }

  void accum(uint64_t offset, Cursor& c) {
    const uint32_t t = targetIndex(c);
    AccumCommand a;
    a.state = readState(c);
    a.op = c.enumIn<AccumOp>("accumulation op", 5);
    a.value = c.f32("accumulation value");
    trace_.commands.push_back({t, offset, std::move(a)});
  }

  void result(Cursor& c) {
    const uint64_t start = c.at();
    const uint32_t t = targetIndex(c);
    if (trace_.results[t]) c.failAt(start, "a second result for framebuffer " + std::to_string(t));
    const Target& target = trace_.targets[t];
    const uint64_t presentAt = c.at();
    const uint8_t present = c.u8("buffers present");
    if (present > 15) c.failAt(presentAt, "buffers present " + std::to_string(present) + ", expected a mask of 4 bits");
    const uint64_t n = uint64_t(target.width) * uint64_t(target.height);
    Buffers b;
    b.width = target.width;
    b.height = target.height;
    b.depthFormat = target.depthFormat;
    if (present & 1) {
      c.need(n * 16, "the colour buffer");
      b.color.resize(n);
      for (glm::vec4& p : b.color)
        for (int i = 0; i < 4; ++i) p[i] = c.f32("a colour");
    }
    if (present & 2) {
      c.need(n * 4, "the depth buffer");
      b.depth.resize(n);
      for (uint32_t& d : b.depth) d = c.u32("a depth code");
    }
    if (present & 4) {
      c.need(n, "the stencil buffer");
      b.stencil.resize(n);
      for (uint8_t& s : b.stencil) s = c.u8("a stencil value");
    }
    if (present & 8) {
      c.need(n * 16, "the accumulation buffer");
      b.accum.resize(n);
      for (glm::vec4& p : b.accum)
        for (int i = 0; i < 4; ++i) p[i] = c.f32("an accumulation value");
    }
    trace_.results[t] = std::move(b);
  }

  std::span<const uint8_t> bytes_;
  ReadLimits limits_;
  Trace trace_;
  uint64_t totalPixels_ = 0;
};

}  // namespace

Trace parseTrace(std::span<const uint8_t> bytes, const ReadLimits& limits) { return Parser(bytes, limits).parse(); }

Trace readTraceFile(const std::string& path, const ReadLimits& limits) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open the file");
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw std::runtime_error("cannot read the file");
  return parseTrace(bytes, limits);
}

}  // namespace shadowref::trace
