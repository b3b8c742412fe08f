// Whole frames through the span loops against the reference path (every fragment through the
// one-fragment function of the pixel history): every method, both depth formats, soft lights,
// PCF and cube maps must give the same bytes in every buffer and the same counters.
#include <catch2/catch.hpp>

#include "raster/renderer.h"
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
  Renderer::useReferencePath(reference);
  FrameResult result = renderFrame(scene, options);
  Renderer::useReferencePath(false);
  return result;
}

}  // namespace

TEST_CASE("span loops give the reference path's bytes for every method", "[spans][determinism]") {
  const auto [file, overrides] = GENERATE(table<std::string, std::vector<std::string>>({
      {"scenes/room.yaml", {"shadow.method=zfail"}},
      {"scenes/room.yaml", {"shadow.method=zpass", "image.depth=unorm24"}},
      {"scenes/room.yaml", {"shadow.method=none"}},
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
