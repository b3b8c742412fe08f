// Scenes and comparisons shared by the extremes suite.
//
// Every extreme starts from one small, hand-checkable scene — a box on a ground slab under a point
// light — and pushes one parameter to its limit (near plane, translation, scale, light position,
// camera position). The rendered stencil is compared with the ray-cast oracle
// (src/oracle/oracle.h), which works in double precision and never touches the
// rasterizer, so what differs is the rasterizer's numerics.
#pragma once

#include <span>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"
#include "shadow/frame_renderer.h"
#include "oracle/oracle.h"

namespace shadowref::extremes {

// Small images: the oracle casts one ray per pixel; smaller still under AddressSanitizer.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr int kWidth = 80, kHeight = 64;
#else
inline constexpr int kWidth = 160, kHeight = 128;
#endif

// Adds `mesh` to the scene and one root node showing it; returns the node's index in roots.
size_t addObject(Scene& scene, const std::string& name, Mesh mesh, const glm::dmat4& local, int material = 0);

// The base scene: a 10 x 10 ground slab with its top at y = 0, a unit box standing on it at the
// origin, a point light at (-1.5, 4, -1), the camera at (4, 3, 5) looking at (0, 0.5, 0), near 0.1,
// P_inf, z-fail. Two materials: 0 grey ground, 1 red box.
Scene boxOnGround(int width = kWidth, int height = kHeight);

// The same picture in other units or elsewhere: every node, the camera (eye, target, near and far)
// and every light mapped by x -> scale * x + offset. Pixel for pixel the image is unchanged in exact
// arithmetic; what changes is the rounding.
Scene similar(const Scene& scene, double scale, const glm::dvec3& offset);

// Rasterized stencil (after the volume pass of light 0) against the oracle for that light.
struct Agreement {
  size_t pixels = 0;
  size_t compared = 0;       // off-edge pixels (oracle nearEdge == 0)
  size_t countMismatch = 0;  // stencil != oracle count (mod 256) among the compared
  size_t surface = 0;        // pixels with a hit
  size_t shadowed = 0;       // oracle: surface pixels the light does not see
  size_t maskDisagree = 0;   // surface pixels where (stencil == 0) != oracle lit
  size_t maskDisagreeOffEdge = 0;
  std::string firstMismatch;

  double countAgreement() const { return compared ? 1.0 - double(countMismatch) / double(compared) : 0.0; }
  double maskAgreement() const { return surface ? 1.0 - double(maskDisagree) / double(surface) : 0.0; }
};

oracle::OracleImage castFor(const Scene& scene, size_t light = 0);
FrameResult renderStencil(const Scene& scene, std::string_view method);

// The oracle count to compare with: z-fail's for ZFail and Auto, z-pass's for ZPass.
Agreement compare(std::span<const uint8_t> stencil, const oracle::OracleImage& img, std::string_view method);
Agreement renderAndCompare(const Scene& scene, std::string_view method, size_t light = 0);

std::string describe(const Agreement& a);

}  // namespace shadowref::extremes
