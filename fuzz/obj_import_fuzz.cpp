// libFuzzer target: the OBJ importer with its material library. The input is an OBJ file; after a
// line "#---mtl" follows the file written as side.mtl next to it (seeds name it with
// "mtllib side.mtl"). Without that line no side.mtl exists, so a dangling mtllib is fuzzed too.
// A SceneError is the correct answer to bad input; anything else is a bug.
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "fuzz/fuzz_support.h"
#include "scene/mesh_import.h"
#include "scene/scene_error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const fuzz::Split parts = fuzz::split({reinterpret_cast<const char*>(data), size}, "\n#---mtl\n");
  fuzz::writeFile("fuzz.obj", parts.main);
  if (parts.found) fuzz::writeFile("side.mtl", parts.side);
  else std::remove("side.mtl");
  std::vector<std::string> warnings;
  try {
    shadowref::loadObj("fuzz.obj", &warnings);
  } catch (const shadowref::SceneError&) {
  }
  return 0;
}
