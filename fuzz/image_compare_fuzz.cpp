// libFuzzer target: the image reading of `shadowref compare`. The first byte chooses the file's
// extension ('p' .png, 'e' .exr, 't' .tif, anything else none, so OpenImageIO guesses from the
// bytes); the rest is written to that file, which is then compared with itself as `compare` does
// (readChannelImage on both, then the comparison). A std::exception is the correct answer to a
// file that cannot be read; a crash, a sanitizer report or an allocation beyond the limit
// fuzz/run.sh sets (a header's size trusted) is a bug.
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>

#include <OpenImageIO/imageio.h>

#include "fuzz/fuzz_support.h"
#include "image/image_compare.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  // One thread: the sanitizers see every read, and each input costs the same.
  OIIO::attribute("threads", 1);
  OIIO::attribute("exr_threads", 1);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const std::string path = data[0] == 'p' ? "fuzz.png" : data[0] == 'e' ? "fuzz.exr" : data[0] == 't' ? "fuzz.tif" : "fuzz";
  fuzz::writeFile(path, {reinterpret_cast<const char*>(data) + 1, size - 1});
  try {
    const shadowref::CompareResult result = shadowref::compareImages(path, path, shadowref::Tolerances{});
    (void)shadowref::formatReport(result);
  } catch (const std::exception&) {
  }
  std::remove(path.c_str());
  return 0;
}
