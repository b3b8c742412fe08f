// Drawing a scene's instances through a pipeline (gl/pipeline.h): the building blocks every shadow
// method's passes are made of (ambient pass, lit pass).
#pragma once

#include <cstddef>
#include <functional>
#include <span>
#include <vector>

#include "gl/lighting.h"
#include "gl/pipeline.h"
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
  // light) — one array for the frame, refilled between passes (the draw contract allows it), so
  // that each pass draws the same one.
  mutable ClipVertexBuffer shadedVertices;
};

// The state to draw an instance with: `state` itself, or for a mirrored instance (det(world) < 0,
// which turns every winding around in window space) a copy in `scratch` with the front face
// flipped, so facing, culling and two-sided stencil see the faces they would unmirrored.
const RenderState& stateFor(const RenderState& state, const Instance& instance, RenderState& scratch);

// A pass's state and its mirrored copy (stateFor), made once for the pass and alive as long as
// it: its draws borrow them until the pass ends (the draw contract, gl/pipeline.h).
struct PassStates {
  RenderState plain, mirrored;
  explicit PassStates(const RenderState& state);
  const RenderState& of(const Instance& instance) const { return instance.mirrored ? mirrored : plain; }
};

// Every instance's vertices transformed for `view`; on the pipeline's threads when one is given
// (forEachIndependent, in ranges of vertices: the same bits, each vertex by itself).
std::vector<PreparedInstance> prepareInstances(const std::vector<Instance>& instances, const SceneView& view,
                                               Pipeline* pipeline = nullptr);

// fn(item, first, last) for the vertices [first, last) of every item, items having counts[item]
// vertices, in ranges of about a thousand: on the pipeline's threads when one is given. Each vertex
// is worked on by itself, so the bits do not depend on the ranges.
void forEachVertexRange(Pipeline* pipeline, std::span<const size_t> counts,
                        const std::function<void(size_t item, size_t first, size_t last)>& fn);

PhongLight toPhongLight(const Light& light);
PhongMaterial toPhongMaterial(const Material& material);

// [Kuhn 2016, §4.3.1]: an object is lit by (and casts a shadow for) a light only when a corner or
// the centre of its bounding box lies within the light's range.
bool withinRange(const Light& light, const Aabb& worldBounds);

// Draws every instance with lighting from `lights` (only those in range of each instance), the
// ambient term included when `includeAmbient`. Per-pixel or Gouraud, as each material says. Its
// draws are one pass with what was drawn or cleared before it, which it ends: the shaders and
// states they borrow are its own.
void drawLit(Pipeline& pipeline, const RenderState& state, const Scene& scene, const SceneView& view,
             std::span<const PreparedInstance> prepared, std::span<const Light> lights, bool includeAmbient,
             DrawKind kind = DrawKind::Lit);

// Ambient light only (step 1 of [Kuhn 2016, §3.1]): fills the depth buffer. Ends the pass.
void drawAmbient(Pipeline& pipeline, const RenderState& state, const Scene& scene, const SceneView& view,
                 std::span<const PreparedInstance> prepared, DrawKind kind = DrawKind::Ambient);

}  // namespace shadowref
