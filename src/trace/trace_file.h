// The trace file (docs/trace-format.md): little-endian records after a header with the format's
// version. Reading checks every size against the bytes that remain and every value against its
// range before anything is allocated or used, so a malformed or truncated file is refused with
// the byte offset of the first thing wrong in it.
#pragma once

#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "gl/render_state.h"
#include "gl/shader_description.h"
#include "scene/resource_limits.h"
#include "trace/trace.h"

namespace shadowref::trace {

// A malformed trace: what is wrong, and where (the byte offset from the start of the file).
class TraceError : public std::runtime_error {
 public:
  TraceError(uint64_t offset, const std::string& message)
      : std::runtime_error("byte " + std::to_string(offset) + ": " + message), offset_(offset) {}
  uint64_t offset() const { return offset_; }

 private:
  uint64_t offset_;
};

// What a trace may ask of a replay: every framebuffer's side and pixels (as a scene's image,
// scene/resource_limits.h), their number and their pixels together. The work of a replay is then
// at most the file's triangles times a framebuffer's pixels.
struct ReadLimits {
  int maxSide = kMaxImageSide;
  uint64_t maxPixels = uint64_t(kMaxImagePixels);
  uint64_t maxTotalPixels = 4 * uint64_t(kMaxImagePixels);
  size_t maxTargets = 1024;
};

// Parses a whole trace; throws TraceError.
Trace parseTrace(std::span<const uint8_t> bytes, const ReadLimits& limits = {});
// Reads and parses the file; throws TraceError (the caller prefixes the path) or, when the file
// cannot be read, std::runtime_error.
Trace readTraceFile(const std::string& path, const ReadLimits& limits = {});

// Appends the little-endian encoding of values to a byte vector; records are framed by
// beginRecord / endRecord (the length is filled in at the end).
class Encoder {
 public:
  explicit Encoder(std::vector<uint8_t>& out) : out_(out) {}
  void u8(uint8_t v) { out_.push_back(v); }
  void u32(uint32_t v);
  void i32(int32_t v) { u32(uint32_t(v)); }
  void u64(uint64_t v);
  void f32(float v);
  void f64(double v);
  void bytes(const void* data, size_t size);
  size_t beginRecord(RecordType type);
  void endRecord(size_t start);
  void header();
  void state(const RenderState& s);
  void shader(const ShaderDescription& d, const std::vector<uint32_t>& textureIds);
  void buffers(uint32_t target, const Buffers& b);

 private:
  std::vector<uint8_t>& out_;
};

}  // namespace shadowref::trace
