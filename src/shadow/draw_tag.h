// What a draw call was, packed into the 32-bit tag the pixel history reports (exec/renderer.h):
// the pass kind in the top 4 bits, the instance index below.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace shadowref {

enum class DrawKind : uint8_t {
  Ambient = 0,      // [Kuhn 2016, §3.1 step 1]
  Lit = 1,          // lit pass, additive
  VolumeSides = 2,  // shadow-volume sides
  FrontCap = 3,
  BackCap = 4,
  Darken = 5,       // [SV slides]: redraw where stencil != 0
  Scene = 6,        // unshadowed scene
  ShadowMap = 7,    // depth from the light
  VolumeView = 8,   // teaching view of the volumes
};

inline uint32_t drawTag(DrawKind kind, int instance) {
  return (uint32_t(kind) << 28) | (uint32_t(instance) & 0x0FFFFFFFu);
}
inline DrawKind drawKindOf(uint32_t tag) { return DrawKind(tag >> 28); }
inline int instanceOf(uint32_t tag) { return int(tag & 0x0FFFFFFFu); }

const char* name(DrawKind kind);

// "lit pass, object 'room/table/top'"
std::string describeDrawTag(uint32_t tag, const std::vector<Instance>& instances);

}  // namespace shadowref
