// libFuzzer target: the scene loader and its -D overrides. The input is a scene file (YAML); each
// line "#D key=value" in it (a comment to YAML) is also passed as a -D override, in order. Mesh
// files are read relative to the working folder, where fuzz/run.sh puts scenes/meshes/. A
// SceneError is the correct answer to bad input; any other exception, a crash, a sanitizer report
// or a timeout is a bug.
#include <cstdint>
#include <string>

#include "scene/scene_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  shadowref::LoadOptions options;
  for (size_t at = 0; (at = text.find("#D ", at)) != std::string::npos; at += 3) {
    const size_t end = text.find('\n', at);
    options.overrides.push_back(text.substr(at + 3, end == std::string::npos ? std::string::npos : end - at - 3));
  }
  try {
    shadowref::loadSceneFromString(text, "fuzz.yaml", options);
  } catch (const shadowref::SceneError&) {
  }
  return 0;
}
