// The camera as the pipeline needs it: view and projection matrices and the viewport.
#pragma once

#include <glm/glm.hpp>

#include "gl/render_state.h"
#include "scene/scene.h"

namespace shadowref {

struct SceneView {
  glm::dmat4 view{1.0};
  glm::dmat4 projection{1.0};
  Viewport viewport;
  double aspect = 1.0;
  bool infinite = false;  // P_inf ([Kuhn 2016, §3.3]): far clipping off
  glm::dvec3 eye{0.0};
};

// P_inf when the camera's far plane is infinite or `forceInfinite` (shadow volumes extrude to
// infinity and need it, [Kuhn 2016, §3.3]); the ordinary frustum otherwise.
SceneView makeCameraView(const Scene& scene, bool forceInfinite = false);

}  // namespace shadowref
