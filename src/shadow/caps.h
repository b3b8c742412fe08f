// The caps that close a shadow volume for z-fail counting ([Kuhn 2016, §3.4, §4.3.3 lines 24-34];
// [SV slides]).
//
//  - front cap: the light-facing triangles exactly as they are, same vertices, same winding. Their
//    depths must equal the scene pass's bit for bit so that LESS fails on them:
//    they index the mesh's own welded vertices, which are the render positions (mesh.h).
//  - back cap: the light-averted triangles with every vertex replaced by its point at infinity
//    (extrusion.h), same winding. Sending a triangle to infinity from a point light scales it about
//    the light, so its normal still points away from the light: out of the volume.
//    For a directional light every vertex goes to the same point; the back cap has no area and is
//    not emitted.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scene/mesh.h"
#include "shadow/extrusion.h"

namespace shadowref {

void appendFrontCap(const Mesh& mesh, const std::vector<uint8_t>& facing, std::vector<glm::uvec3>& out);

// Appends nothing for a shared (directional) point at infinity.
void appendBackCap(const Mesh& mesh, const std::vector<uint8_t>& facing, const InfiniteIndexing& infinite,
                   std::vector<glm::uvec3>& out);

}  // namespace shadowref
