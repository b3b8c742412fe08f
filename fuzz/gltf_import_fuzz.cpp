// libFuzzer target: the glTF importer, JSON (.gltf) and binary (.glb), with an external buffer.
// The first byte chooses the file name: 'b' fuzz.glb, anything else fuzz.gltf; after a line
// "#---bin" follows the file written as side.bin next to it (seeds name it as a buffer "uri").
// Without that line no side.bin exists. A SceneError is the correct answer; anything else is a bug.
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "fuzz/fuzz_support.h"
#include "scene/mesh_import.h"
#include "scene/scene_error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const std::string path = data[0] == 'b' ? "fuzz.glb" : "fuzz.gltf";
  const fuzz::Split parts = fuzz::split({reinterpret_cast<const char*>(data) + 1, size - 1}, "\n#---bin\n");
  fuzz::writeFile(path, parts.main);
  if (parts.found) fuzz::writeFile("side.bin", parts.side);
  else std::remove("side.bin");
  std::vector<std::string> warnings;
  try {
    shadowref::loadGltf(path, &warnings);
  } catch (const shadowref::SceneError&) {
  }
  std::remove(path.c_str());
  return 0;
}
