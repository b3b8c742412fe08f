// Whole frames through the span kernels against the renderer run one fragment at a time
// (Renderer::oneFragmentAtATime: every fragment through the one-fragment function of the pixel
// history): every method, both depth formats, soft lights, PCF and cube maps must give the same
// bytes in every buffer and the same counters.
#include <algorithm>

#include <catch2/catch.hpp>

#include "exec/renderer.h"
#include "scene/scene_loader.h"
#include "shadow/frame_renderer.h"
#include "support/frame_compare.h"

using namespace shadowref;
using shadowref::testing::requireIdenticalFrames;

namespace {

FrameResult render(const Scene& scene, bool reference, int threads) {
  FrameOptions options;
  options.threads = threads;
  options.keepStencil = true;
  Renderer::oneFragmentAtATime(reference);
  FrameResult result = renderFrame(scene, options);
  Renderer::oneFragmentAtATime(false);
  return result;
}

}  // namespace

TEST_CASE("span kernels give the one-fragment path's bytes for every method", "[spans][determinism]") {
  const auto [file, overrides] = GENERATE(table<std::string, std::vector<std::string>>({
      {"scenes/room.yaml", {"shadow.method=zfail"}},
      {"scenes/room.yaml", {"shadow.method=zpass", "image.depth=unorm24"}},
      {"scenes/room.yaml", {"shadow.method=none"}},
      {"scenes/room.yaml", {"shadow.method=zfail", "materials.wall.shading=gouraud", "materials.floor.shading=gouraud"}},
      {"scenes/directional.yaml", {"shadow.method=zpass"}},
      {"scenes/directional.yaml", {"shadow.method=shadowmap", "shadow.pcf=3", "shadow.map_size=128"}},
      {"scenes/room.yaml", {"shadow.method=shadowmap", "shadow.map_size=128"}},
      {"scenes/room.yaml", {"shadow.method=zfail", "lights.0.soft.shape=square_y", "lights.0.soft.spacing=0.3"}},
      {"scenes/pumpkins.yaml", {"shadow.method=auto"}},
      {"scenes/city16.yaml", {"shadow.method=zfail"}},
      {"scenes/outdoor.yaml", {"shadow.method=tsm", "shadow.map_size=256"}},
      {"scenes/spot.yaml", {"shadow.method=shadowmap", "shadow.pcf=3", "shadow.map_size=128"}},
      {"scenes/spot.yaml", {"lights.0.soft.shape=area16", "lights.0.soft.spacing=0.6", "shadow.map_size=64"}},
  }));
  LoadOptions options;
  options.overrides = overrides;
  options.overrides.push_back("image.width=160");
  options.overrides.push_back("image.height=128");
  const Scene scene = loadScene(std::string(SHADOWREF_SOURCE_DIR) + "/" + file, options);
  INFO(file);
  const FrameResult reference = render(scene, true, 1);
  REQUIRE(reference.stats.fragments > 0);
  requireIdenticalFrames(reference, render(scene, false, 1));
  requireIdenticalFrames(reference, render(scene, false, 2));
}

TEST_CASE("a Gouraud material's ambient pass is its exact ambient term", "[spans][lighting]") {
  // With no light every vertex gets global ambient * ambient; the pass draws that constant, so
  // every pixel of the material holds its float, whatever the triangle's shape.
  LoadOptions options;
  for (const char* m : {"default", "wall", "floor", "wood", "chair"})
    options.overrides.push_back(std::string("materials.") + m + ".shading=gouraud");
  options.overrides.push_back("shadow.method=zfail");
  options.overrides.push_back("image.width=160");
  options.overrides.push_back("image.height=128");
  const Scene scene = loadScene(std::string(SHADOWREF_SOURCE_DIR) + "/scenes/room.yaml", options);
  std::vector<glm::vec4> allowed;
  for (const Material& m : scene.materials) allowed.push_back(glm::vec4(glm::vec3(scene.ambient * m.ambient), 1.0f));
  FrameOptions frame;
  PixelVector<glm::vec4> ambient;
  frame.onPass = [&](const std::string& pass, const Framebuffer& fb) {
    if (pass == "01-ambient") ambient = fb.color();
  };
  renderFrame(scene, frame);
  REQUIRE(ambient.size() == size_t(160 * 128));
  size_t wall = 0;
  for (const glm::vec4& c : ambient) {
    INFO("colour " << c.r << " " << c.g << " " << c.b << " " << c.a);
    REQUIRE(std::find(allowed.begin(), allowed.end(), c) != allowed.end());  // the room is closed: no background
    wall += c == allowed[1];
  }
  REQUIRE(wall > 160 * 128 / 4);  // the walls and ceiling fill much of the view
}
