// libFuzzer target for everything that reads user input: the scene loader with its
// -D overrides, and the OBJ and glTF importers through a temporary file. A SceneError is the
// correct answer to bad input; anything else escaping, a crash or a sanitizer report is a bug.
//
// Input layout, so one corpus drives all paths: the first byte chooses the path
//   0..191  : the rest is a scene file (YAML); a line "#D key=value" also becomes a -D override
//   192..223: the rest is an OBJ file
//   224..255: the rest is a glTF (JSON) file
// Built and run by fuzz/run.sh.
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <unistd.h>

#include "scene/mesh_import.h"
#include "scene/scene_loader.h"

namespace {

std::string tempPath(const char* extension) {
  return "/tmp/shadowref_fuzz_" + std::to_string(getpid()) + extension;
}

void importFile(const std::string& text, const char* extension, bool gltf) {
  const std::string path = tempPath(extension);
  {
    std::ofstream out(path, std::ios::binary);
    out << text;
  }
  try {
    if (gltf) shadowref::loadGltf(path);
    else shadowref::loadObj(path);
  } catch (const shadowref::SceneError&) {
  }
  std::remove(path.c_str());
}

void loadScene(const std::string& text) {
  shadowref::LoadOptions options;
  size_t at = 0;
  while ((at = text.find("#D ", at)) != std::string::npos) {
    size_t end = text.find('\n', at);
    options.overrides.push_back(text.substr(at + 3, end == std::string::npos ? std::string::npos : end - at - 3));
    at += 3;
  }
  try {
    shadowref::loadSceneFromString(text, "fuzz.yaml", options);
  } catch (const shadowref::SceneError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const std::string text(reinterpret_cast<const char*>(data + 1), size - 1);
  if (data[0] < 192) loadScene(text);
  else if (data[0] < 224) importFile(text, ".obj", false);
  else importFile(text, ".gltf", true);
  return 0;
}
