// libFuzzer target: the shadowref command line. Each line of the input is one argument; they are
// parsed by the program's own parser (cli/command_line.h) and the chosen subcommand runs: render,
// check, info and compare, with the validation of every option and value. `bench`, `explore` and
// `sweep` are parsed but not run (bench and sweep time frames, a sweep file's parser has its tests
// in tests/sweep; explore serves until it is stopped).
//
// Bounds, so that each input is cheap and stays in the scratch folder fuzz/run.sh runs this in
// (it holds minimal.yaml at 16x16, bad.yaml, a.png and b.exr, which inputs name by name):
// an argument with a '/' is not tried (no path outside the folder, no /dev/zero); render gets
// "-D image.width=16 -D image.height=16 -D shadow.map_size=64" after the input's own overrides
// and one thread; a frame sequence at most 4 frames and no movie. Every file a run leaves is removed after it, and the four files are restored
// (an input may name one as its output).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>

#include "cli/command_line.h"
#include "fuzz/fuzz_support.h"

namespace {

std::map<std::filesystem::path, std::string> fixtures;  // path -> contents

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  for (const auto& entry : std::filesystem::directory_iterator(".")) {
    std::ifstream in(entry.path(), std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    fixtures[entry.path()] = bytes.str();
  }
  fuzz::silenceStreams();
  OIIO::attribute("threads", 1);
  OIIO::attribute("exr_threads", 1);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  if (text.find('/') != std::string::npos) return 0;
  std::vector<std::string> args{"shadowref"};
  for (size_t at = 0; at <= text.size();) {
    const size_t end = std::min(text.find('\n', at), text.size());
    args.push_back(text.substr(at, end - at));
    at = end + 1;
  }
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());

  using namespace shadowref::cli;
  CLI::App app;
  CommandArgs parsed;
  addCommands(app, parsed);
  if (parseCommandLine(app, int(argv.size()), argv.data())) return 0;
  if (app.got_subcommand("bench") || app.got_subcommand("explore") || app.got_subcommand("sweep"))
    return 0;  // timing; a server; timing
  // A frame sequence renders every frame of its range, and a movie runs ffmpeg: a valid range is
  // tried only up to 4 frames and without a movie (a bad range or movie name is still checked).
  const SequenceArgs& sequence = parsed.render.sequence;
  std::string rangeError;
  if (const std::optional<FrameRange> range = parseFrameRange(sequence.frames, rangeError);
      range && (range->count() > 4 || !sequence.gif.empty() || !sequence.mp4.empty() || !sequence.movie.empty()))
    return 0;
  for (const char* bound : {"image.width=16", "image.height=16", "shadow.map_size=64"})
    parsed.render.scene.overrides.push_back(bound);
  parsed.render.threads = 1;
  runCommand(app, parsed);

  std::error_code ignored;
  for (const auto& entry : std::filesystem::directory_iterator("."))
    if (!fixtures.count(entry.path())) std::filesystem::remove_all(entry.path(), ignored);
  for (const auto& [path, bytes] : fixtures) fuzz::writeFile(path, bytes);
  return 0;
}
