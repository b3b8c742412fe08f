// `shadowref render [SCENE] [-o OUT]...`: renders a scene to PNG and/or EXR, with the teaching dumps.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "cli/cli_common.h"
#include "cli/frame_sequence.h"
#include "gl/framebuffer.h"

namespace CLI {
class App;
}

namespace shadowref::cli {

struct RenderArgs {
  SceneArgs scene;
  std::vector<std::string> outputs;  // .png / .exr
  std::string method;                // overrides shadow.method
  int threads = 0;                   // 0: all cores
  std::string pipeline = "fast";     // reference, fast
  bool quiet = false;
  bool stats = false;
  std::vector<std::string> dumps;    // passes, stencil, depth
  std::string dumpRegion;            // "x,y,w,h": stencil counts of that region as a grid
  std::string view;                  // volumes, volumes-overlay
  std::string pixelHistory;          // "x,y"
  std::string exrCompression = "rle";  // none, rle, zip
  bool oracle = false;               // per light: the ray-traced visibility and an error map
  std::string stencilView;           // "", unsigned, signed: how stencil bytes read ("": unsigned)
  SequenceArgs sequence;             // --frames, --fps, --gif, --mp4, --movie, --contact-sheet
  std::string capture;               // trace file of the frame's commands (src/trace)
};

void addRenderCommand(CLI::App& app, RenderArgs& args);
int runRender(const RenderArgs& args);

// How renderScene differs for one frame of a sequence (frame_sequence.h) from a still.
struct FrameHooks {
  std::vector<std::string> outputs;  // the files to write instead of args.outputs (empty: those)
  bool listWrites = true;            // "wrote FILE" on stderr for each file
  std::vector<std::pair<std::string, std::string>> metadata;  // added to every file's attributes
  std::function<void(const Framebuffer&)> onFrame;           // the frame, after its files are written
};

// Renders one still scene (animation already evaluated) with the flags of args: the body of
// `render` after loading. Exit status as runRender's.
int renderScene(const RenderArgs& args, const Scene& scene, const FrameHooks& hooks);

}  // namespace shadowref::cli
