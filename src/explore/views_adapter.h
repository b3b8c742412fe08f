// The explorer's pictures and per-pixel answers, made from a loaded scene. This file is the one
// place where the explorer reaches the renderer and the teaching views: everything the page shows
// comes through these functions, so that a shared views module can take their place in one file.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "gl/pipeline.h"
#include "scene/scene.h"

namespace shadowref::explore {

// What the page can look at. Each is rendered from the same scene with the same options as
// `shadowref render` would use; only `Frame` is a picture of the scene itself.
enum class View : uint8_t {
  Frame,       // the finished frame: the bytes `shadowref render` writes
  Stencil,     // one light's stencil counts in false colour (--dump stencil)
  Volumes,     // front faces and back faces of the volumes over the frame (--view volumes)
  Overlay,     // translucent volumes over the frame (--view volumes-overlay)
  Depth,       // linear eye depth, ranged to the nearest and farthest drawn pixel
  ShadowMap,   // one light's shadow map, ranged to its nearest and farthest stored depth
  Visibility,  // one scene light's visibility, white lit, black in shadow (--dump visibility)
  Pass,        // the frame as it stood after one pass (--dump passes)
};

// "frame", "stencil", ...: the names the page and the export use; false for an unknown one.
bool parseView(const std::string& name, View& view);
const char* viewName(View view);

struct ViewRequest {
  View view = View::Frame;
  int index = 0;               // the light (stencil, shadow map, visibility) or pass number
  bool signedCounts = false;   // stencil: read 128..255 as -128..-1
};

// One picture, top row first, RGBA, and per pixel the value the page shows under the mouse.
struct ViewImage {
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;
  // "count" (stencil), "depth", "visibility", "" for none; one value per pixel, top row first.
  std::string valueName;
  std::vector<float> values;
  nlohmann::json info;  // range, legend, names of the lights / maps / passes there are
};

// Renders the view (std::invalid_argument for an index there is none of, std::runtime_error for
// a view this method has nothing to show in). `pipelines` makes the fast pipelines of every frame
// the explorer renders, so that consecutive frames share its threads.
ViewImage renderView(const Scene& scene, const ViewRequest& request, const PipelineMaker& pipelines);

// The history of pixel (x, y) (framebuffer coordinates, row 0 at the bottom) as `render
// --pixel-history` prints it, from the same views::PixelHistory: in order, every fragment with its
// pass, light, object, facing, depths, test outcomes and stencil before and after, every clear of
// the pixel (the stencil clear before each light's volumes), and for a shadow-map method each
// lookup of a shaded fragment (light-space coordinates, texel, stored depth, compared r, result);
// stencil values unsigned, or signed (128..255 as -128..-1). Also the pixel's final colour and
// its visibility and stencil count per light.
nlohmann::json pixelHistory(const Scene& scene, int x, int y, bool signedCounts = false);

// The scene as the page's controls need it: image size, camera, lights, shadow settings, the
// methods there are.
nlohmann::json sceneSummary(const Scene& scene);

// Statistics of the frame: triangles, fragments, per-light notes and time per pass.
nlohmann::json frameStatistics(const Scene& scene, const PipelineMaker& pipelines);

}  // namespace shadowref::explore
