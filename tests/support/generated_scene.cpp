#include "support/generated_scene.h"

#include "scene/scene_loader.h"

namespace shadowref::testing {

Scene generatedScene(const std::string& generator, const std::string& method, int width, int height) {
  LoadOptions options;
  options.overrides = {"image.width=" + std::to_string(width), "image.height=" + std::to_string(height),
                       "shadow.method=" + method};
  return loadSceneFromString("generator: {type: " + generator + "}\n", "<" + generator + ">", options);
}

}  // namespace shadowref::testing
