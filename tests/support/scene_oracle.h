// What the tests that hold frames and shadow maps against the ray-cast oracle (src/oracle)
// set up alike: a scene of scenes/ at a test's image size, the lights the volume renderer draws,
// a frame with its stencil kept, the oracle cast as the volume renderer projects, and one light's
// shadow map built as a frame builds it.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "oracle/oracle.h"
#include "scene/scene.h"
#include "shadow/frame_renderer.h"
#include "shadow/light_shadow.h"

namespace shadowref::testing {

// scenes/<file> (the file name with its extension) at width × height, then `overrides` (-D's
// KEY=VALUE) in their order.
Scene sceneAtSize(const std::string& file, int width, int height, const std::vector<std::string>& overrides = {});

// The lights the volume renderer draws, soft lights expanded, in its order ("L0", "L1", ...).
std::vector<Light> drawnLights(const Scene& scene);

// A frame by `method` with each light's stencil after its volume pass kept.
FrameResult renderWithStencil(const Scene& scene, std::string_view method);

// The oracle for `light` with the infinite projection the volume renderer draws with
// ([Kuhn 2016, §3.3]).
oracle::OracleImage castVolumeOracle(const Scene& scene, const Light& light);

// The first light's shadow map(s), built as a frame builds them (trapezoidal: TSM), through a fast
// pipeline on every core.
std::unique_ptr<LightShadow> firstLightShadow(const Scene& scene, bool trapezoidal);

}  // namespace shadowref::testing
