#include "support/scene_oracle.h"

#include "scene/scene_loader.h"
#include "shadow/scene_view.h"
#include "shadow/soft_lights.h"

namespace shadowref::testing {

Scene sceneAtSize(const std::string& file, int width, int height, const std::vector<std::string>& overrides) {
  LoadOptions options;
  options.overrides = {"image.width=" + std::to_string(width), "image.height=" + std::to_string(height)};
  options.overrides.insert(options.overrides.end(), overrides.begin(), overrides.end());
  return loadScene(std::string(SHADOWREF_SOURCE_DIR) + "/scenes/" + file, options);
}

std::vector<Light> drawnLights(const Scene& scene) {
  std::vector<Light> lights;
  for (const Light& light : scene.lights)
    for (const Light& l : expandSoftLight(light)) lights.push_back(l);
  return lights;
}

FrameResult renderWithStencil(const Scene& scene, std::string_view method) {
  FrameOptions options;
  options.method = method;
  options.keepStencil = true;
  return renderFrame(scene, options);
}

oracle::OracleImage castVolumeOracle(const Scene& scene, const Light& light) {
  oracle::OracleOptions options;
  options.forceInfiniteProjection = true;
  return oracle::castOracle(scene, light, options);
}

std::unique_ptr<LightShadow> firstLightShadow(const Scene& scene, bool trapezoidal) {
  RasterStats stats;
  Framebuffer frame(1, 1);  // the maps' pipelines are made like this one: on every core
  return buildLightShadow(scene, scene.instances(), makeCameraView(scene), scene.lights.at(0), trapezoidal,
                          *makePipeline(PipelineKind::Fast, frame, 0), stats);
}

}  // namespace shadowref::testing
