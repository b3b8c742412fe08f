#include "shadow/scene_view.h"

#include <cmath>

#include "gl/projection.h"

namespace shadowref {

SceneView makeCameraView(const Scene& scene, bool forceInfinite) {
  const Camera& c = scene.camera;
  SceneView v;
  v.aspect = double(scene.width) / double(scene.height);
  v.view = lookAt(c.eye, c.target, c.up);
  v.infinite = forceInfinite || std::isinf(c.farPlane);
  v.projection = v.infinite ? infinitePerspective(c.fovYDegrees, v.aspect, c.nearPlane)
                            : perspective(c.fovYDegrees, v.aspect, c.nearPlane, c.farPlane);
  v.viewport = Viewport{0, 0, scene.width, scene.height, 0.0, 1.0};
  v.eye = c.eye;
  return v;
}

}  // namespace shadowref
