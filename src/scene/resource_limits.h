// The resource budget of a scene: how much a scene may ask the renderer to allocate, checked when
// the scene is loaded — before any instance is flattened or prepared — so that a small hostile
// file (YAML aliases that repeat a large mesh, a deep scene graph) is rejected with a message
// instead of exhausting memory. Also the magnitude bound on every number of a scene, which keeps
// the quantities derived from them (squared distances, matrix products, window coordinates)
// finite. Header-only: the image and dump code use the image limits without the scene library.
// The limits are documented in docs/scene-format.md, "Resource limits".
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "scene/checked_arithmetic.h"

namespace shadowref {

// Hard limits on the image: beyond them the buffers cannot sensibly be allocated (every buffer
// of a 2^26-pixel frame together takes about 2.5 GB).
inline constexpr int kMaxImageSide = 16384;
inline constexpr long long kMaxImagePixels = 1LL << 26;

// width x height, or nullopt when a side is not in 1 … kMaxImageSide or the product exceeds
// kMaxImagePixels: the one test every allocation of an image-sized buffer from input passes.
[[nodiscard]] constexpr std::optional<std::uint64_t> imagePixels(std::uint64_t width, std::uint64_t height) {
  if (width == 0 || height == 0 || width > std::uint64_t(kMaxImageSide) || height > std::uint64_t(kMaxImageSide))
    return std::nullopt;
  const std::optional<std::uint64_t> pixels = checkedMul(width, height);
  if (!pixels || *pixels > std::uint64_t(kMaxImagePixels)) return std::nullopt;
  return pixels;
}

// Every number written in a scene (file or -D) has magnitude at most this. Squares and products
// of three such numbers stay far inside a double's range, so lengths, dot products, matrices and
// light frusta computed from them are finite.
inline constexpr double kMaxSceneNumber = 1e15;
// A node's world transform (every entry) and an instance's world bounds stay within this: what
// nesting and mesh coordinates make of the bounded numbers above.
inline constexpr double kMaxWorldMagnitude = 1e30;

// Animation (the `animation:` section, `render --frames`): keys per track, and the frames and
// frame rate one command may ask for. Evaluating a track is a binary search over its keys; a
// sequence holds one frame at a time, so these bound the work, not memory.
inline constexpr std::size_t kMaxAnimationKeys = 1u << 16;
inline constexpr double kMaxAnimationFps = 1000.0;
inline constexpr std::int64_t kMaxFrameNumber = 9'999'999;  // frame numbers 0 … this
inline constexpr std::int64_t kMaxSequenceFrames = 100'000;  // frames in one --frames range

// What a scene may make the renderer allocate, counted over the flattened scene graph (each
// mesh node is one instance; a mesh used by n nodes counts n times). The `limits:` section of a
// scene file or `-D limits.KEY=N` raises or lowers them.
struct ResourceLimits {
  std::uint64_t maxInstances = 1u << 17;  // mesh nodes after flattening
  std::uint64_t maxTriangles = 1u << 24;  // triangles of every instance, summed
  // Render vertices of every instance, summed: each is transformed into one 160-byte clip vertex
  // per view (two with a Gouraud material), so the default bounds that at about 2.7 GB.
  std::uint64_t maxVertices = 1u << 23;
};

inline constexpr ResourceLimits kDefaultResourceLimits{};

// Running totals of a scene's instances against a budget: add() one instance at a time, and
// stop at the first that does not fit (its message names the limit and how to raise it).
// Importers that expand instances themselves (a glTF node graph) use it the same way.
class ResourceBudget {
 public:
  explicit ResourceBudget(const ResourceLimits& limits = kDefaultResourceLimits) : limits_(limits) {}

  // Counts `copies` instances of a mesh with `triangles` triangles and `vertices` vertices.
  // Returns "" when they fit, else the message (nothing is counted then).
  [[nodiscard]] std::string add(std::uint64_t triangles, std::uint64_t vertices, std::uint64_t copies = 1) {
    const std::optional<std::uint64_t> instances = checkedAdd(instances_, copies);
    if (!instances || *instances > limits_.maxInstances)
      return exceeded("instances", "max_instances", limits_.maxInstances);
    const std::optional<std::uint64_t> tris = checkedMulAdd(triangles, copies, triangles_);
    if (!tris || *tris > limits_.maxTriangles)
      return exceeded("triangles after instancing", "max_triangles", limits_.maxTriangles);
    const std::optional<std::uint64_t> verts = checkedMulAdd(vertices, copies, vertices_);
    if (!verts || *verts > limits_.maxVertices)
      return exceeded("vertices after instancing", "max_vertices", limits_.maxVertices);
    instances_ = *instances;
    triangles_ = *tris;
    vertices_ = *verts;
    return {};
  }

  std::uint64_t instances() const { return instances_; }
  std::uint64_t triangles() const { return triangles_; }
  std::uint64_t vertices() const { return vertices_; }

 private:
  static std::string exceeded(const char* what, const char* key, std::uint64_t limit) {
    return std::string("the scene needs more than ") + std::to_string(limit) + " " + what + " (the limit limits." +
           key + "; raise it with 'limits: {" + key + ": N}' in the scene or -D limits." + key + "=N)";
  }

  ResourceLimits limits_;
  std::uint64_t instances_ = 0, triangles_ = 0, vertices_ = 0;
};

}  // namespace shadowref
