// Drawing a scene's instances through the raster pipeline: the building blocks every shadow
// method's passes are made of (ambient pass, lit pass, depth-only pass).
#pragma once

#include <cstddef>
#include <functional>
#include <span>
#include <vector>

#include "gl/lighting.h"
#include "exec/renderer.h"
#include "gl/vertex.h"
#include "gl/vertex_stage.h"
#include "scene/scene.h"
#include "shadow/draw_tag.h"
#include "shadow/scene_view.h"

namespace shadowref {

// An instance transformed for one view, once per frame: clip positions plus world position and
// world normal as varyings (lighting.h layout), reused by every pass that draws it.
struct PreparedInstance {
  const Instance* instance = nullptr;
  int index = 0;                 // position in the scene's instance list (pixel-history tag)
  VertexTransform transform;     // object -> clip; shadow volumes of this instance must use it too
  ClipVertexBuffer vertices;
  std::span<const uint32_t> indices;  // the mesh's own (triangleIndices)
  // A Gouraud material's vertices as its passes draw them: the clip positions of `vertices`, the
  // varyings each vertex's colour for the pass (drawLit; the shadow maps' camera pass, a colour per
  // light) — one array for the frame, so that each pass draws the same one.
  mutable ClipVertexBuffer shadedVertices;
  // The setups of its scene draws (ambient, then each light's lit pass: the same triangles in a
  // state that sets them up alike), kept for the frame's next pass.
  mutable SetupReuse setups;
};

// The state to draw an instance with: `state` itself, or for a mirrored instance (det(world) < 0,
// which turns every winding around in window space) a copy in `scratch` with the front face
// flipped, so facing, culling and two-sided stencil see the faces they would unmirrored.
const RenderState& stateFor(const RenderState& state, const Instance& instance, RenderState& scratch);

// Every instance's vertices transformed for `view`; on the renderer's threads when one is given
// (in ranges of vertices: the same bits, each vertex by itself).
std::vector<PreparedInstance> prepareInstances(const std::vector<Instance>& instances, const SceneView& view,
                                               Renderer* renderer = nullptr);
// The same into `out`, whose instances keep the buffers they grew in the last call (their setups
// forgotten).
void prepareInstancesInto(const std::vector<Instance>& instances, const SceneView& view, Renderer* renderer,
                          std::vector<PreparedInstance>& out);
// The same into one list kept on the calling thread from frame to frame, for a frame's passes:
// valid until the next call on this thread. Made anew each frame, the city's 129 instances
// allocated and freed about 650 buffers a frame on the calling thread while the other threads
// waited.
std::span<const PreparedInstance> prepareFrameInstances(const std::vector<Instance>& instances, const SceneView& view,
                                                        Renderer& renderer);

// fn(item, first, last) for the vertices [first, last) of every item, items having counts[item]
// vertices, in ranges of about a thousand: on the renderer's threads when one is given. Each vertex
// is worked on by itself, so the bits do not depend on the ranges.
void forEachVertexRange(Renderer* renderer, std::span<const size_t> counts,
                        const std::function<void(size_t item, size_t first, size_t last)>& fn);

PhongLight toPhongLight(const Light& light);
PhongMaterial toPhongMaterial(const Material& material);

// [Kuhn 2016, §4.3.1]: an object is lit by (and casts a shadow for) a light only when a corner or
// the centre of its bounding box lies within the light's range.
bool withinRange(const Light& light, const Aabb& worldBounds);

// Draws every instance with lighting from `lights` (only those in range of each instance), the
// ambient term included when `includeAmbient`. Per-pixel or Gouraud, as each material says.
void drawLit(Renderer& renderer, const RenderState& state, const Scene& scene, const SceneView& view,
             std::span<const PreparedInstance> prepared, std::span<const Light> lights, bool includeAmbient,
             DrawKind kind = DrawKind::Lit);

// Ambient light only (step 1 of [Kuhn 2016, §3.1]): fills the depth buffer.
void drawAmbient(Renderer& renderer, const RenderState& state, const Scene& scene, const SceneView& view,
                 std::span<const PreparedInstance> prepared, DrawKind kind = DrawKind::Ambient);

// Depth (and stencil) only, no colour.
void drawDepthOnly(Renderer& renderer, const RenderState& state, std::span<const PreparedInstance> prepared,
                   DrawKind kind = DrawKind::ShadowMap);

}  // namespace shadowref
