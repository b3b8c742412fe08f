// libFuzzer target: the numbers of a scene, rendered. The scene is fixed and valid (a 16x16 image,
// a point, a spot and a directional light, a ground slab, a box, a sphere); the input only
// supplies its numbers, so every input gets past the parser and the fuzzer spends its time on
// extreme values: huge, tiny, denormal, negative zero, long digit strings, "infinite" where the
// format allows it, and text the loader must refuse. The input is split at whitespace into
// tokens; token i replaces slot i of the skeleton below (a missing or empty token keeps the
// slot's value), with every character that could change the YAML structure dropped. A scene the
// loader accepts is rendered with each shadow method; a SceneError or a std::exception from the
// renderer (a method refusing a scene) is a correct answer, a crash, a sanitizer report (float
// to integer overflow included) or a timeout is a bug.
#include <cctype>
#include <cstdint>
#include <exception>
#include <string>
#include <vector>

#include "scene/scene_loader.h"
#include "shadow/frame_renderer.h"
#include "shadow/technique_registry.h"

namespace {

// "@" marks a slot; the comments name them in order.
constexpr const char* kSkeleton = R"(image: {width: 16, height: 16}
camera: {eye: [@, @, @], target: [@, @, @], up: [@, @, @], fov: @, near: @, far: @}
ambient: @
lights:
  - {name: bulb, type: point, position: [@, @, @], color: [@, @, @], range: @, attenuation: [@, @, @]}
  - {name: spot, type: spot, position: [@, @, @], direction: [@, @, @], spot_cutoff: @, spot_exponent: @}
  - {name: sun, type: directional, direction: [@, @, @], color: @}
materials:
  red: {diffuse: @, specular: @, shininess: @}
meshes:
  ground: {plane: {size: [@, @], thickness: @}}
  box: {box: {size: [@, @, @]}}
  ball: {sphere: {radius: @, slices: 8, stacks: 4}}
nodes:
  - {name: ground, mesh: ground}
  - {name: box, mesh: box, material: red, translate: [@, @, @], scale: [@, @, @], rotate: {axis: [@, @, @], angle: @}}
  - {name: ball, mesh: ball, translate: [@, @, @]}
shadow: {map_size: 64, offset_factor: @, offset_units: @, bias: @, compare_fail: @, focus_region: @}
)";

// The values of the slots in order: the scene of scenes/minimal.yaml, more or less.
const std::vector<std::string> kDefaults = {
    "4", "3", "5", "0", "0.5", "0", "0", "1", "0", "50", "0.1", "infinite",  // camera
    "0.15",                                                                // ambient
    "2", "4", "1", "1", "1", "1", "infinite", "1", "0", "0",              // bulb
    "-2", "5", "0", "0.3", "-1", "0", "35", "4",                          // spot
    "-0.4", "-1", "-0.3", "0.5",                                          // sun
    "0.8", "0.4", "40",                                                   // red
    "8", "8", "0.1", "1", "1", "1", "0.5",                                // ground, box, ball
    "0", "0.5", "0", "1", "1", "1", "0", "1", "0", "30", "1.5", "0.5", "1",  // nodes
    "1.1", "4", "0", "0.4", "0.4",                                        // shadow
};

bool keeps(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '+' || c == '_'; }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::vector<std::string> tokens;
  std::string token;
  for (size_t i = 0; i <= size; ++i) {
    const char c = i < size ? char(data[i]) : ' ';
    if (std::isspace(static_cast<unsigned char>(c))) {
      tokens.push_back(token);
      token.clear();
    } else if (keeps(c)) {
      token += c;
    }
  }
  std::string yaml;
  size_t slot = 0;
  for (const char* p = kSkeleton; *p; ++p) {
    if (*p != '@') {
      yaml += *p;
      continue;
    }
    yaml += slot < tokens.size() && !tokens[slot].empty() ? tokens[slot] : kDefaults.at(slot);
    ++slot;
  }
  shadowref::Scene scene;
  try {
    scene = shadowref::loadSceneFromString(yaml, "values.yaml");
  } catch (const shadowref::SceneError&) {
    return 0;
  }
  for (const shadowref::ShadowTechnique* technique : shadowref::techniques()) {
    shadowref::FrameOptions options;
    options.method = technique->name;
    options.threads = 1;
    try {
      shadowref::renderFrame(scene, options);
    } catch (const std::exception&) {
    }
  }
  return 0;
}
