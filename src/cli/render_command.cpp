#include "cli/render_command.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "image/image_writer.h"
#include "shadow/frame_renderer.h"
#include "shadow/shadow_method.h"

namespace shadowref::cli {

namespace {

// Prints every fragment that reached the watched pixel: the answer to "why is this pixel dark?".
class PixelHistoryPrinter final : public FragmentObserver {
 public:
  explicit PixelHistoryPrinter(const std::vector<Instance>& instances) : instances_(instances) {}
  void onFragment(const FragmentEvent& e) override {
    std::ostringstream line;
    line << "draw " << e.drawIndex << "  " << describeTag(e.drawTag) << "  "
         << (e.facing == FrontFacing ? "front" : "back") << "  z=" << e.depth << " (stored " << e.storedDepth
         << ")  stencil test " << (e.stencilPassed ? "pass" : "FAIL") << "  depth test "
         << (!e.stencilPassed ? "-" : e.depthPassed ? "pass" : "FAIL") << "  stencil " << int(e.stencilBefore)
         << " -> " << int(e.stencilAfter);
    if (e.colorAfter != e.colorBefore)
      line << "  colour (" << e.colorAfter.r << ", " << e.colorAfter.g << ", " << e.colorAfter.b << ")";
    lines_.push_back(line.str());
  }
  const std::vector<std::string>& lines() const { return lines_; }

 private:
  std::string describeTag(uint32_t tag) const {
    if (tag < instances_.size()) return "object '" + instances_[tag].path + "'";
    return "tag " + std::to_string(tag);
  }
  const std::vector<Instance>& instances_;
  std::vector<std::string> lines_;
};

bool parsePixel(const std::string& text, int& x, int& y) {
  char comma = 0;
  std::istringstream in(text);
  return bool(in >> x >> comma >> y) && comma == ',' && in.peek() == EOF;
}

std::string passPath(const std::string& output, const std::string& pass) {
  std::filesystem::path p(output);
  const std::string stem = p.stem().string();
  return (p.parent_path() / (stem + ".pass-" + pass + ".png")).string();
}

void printStats(const FrameResult& frame) {
  const RasterStats& s = frame.stats;
  std::cerr << "triangles in " << s.trianglesIn << ", clipped " << s.trianglesClipped << ", culled "
            << s.trianglesCulled << ", rasterized " << s.trianglesRasterized << "\n"
            << "fragments " << s.fragments << ", stencil failed " << s.stencilFailed << ", depth failed "
            << s.depthFailed << ", stencil writes " << s.stencilWrites << ", colour writes " << s.colorWrites
            << "\n";
  for (const std::string& note : frame.notes) std::cerr << note << '\n';
  for (const PassTiming& t : frame.timings) std::fprintf(stderr, "time %-24s %9.3f ms\n", t.pass.c_str(), t.milliseconds);
}

}  // namespace

void addRenderCommand(CLI::App& app, RenderArgs& args) {
  CLI::App* render = app.add_subcommand("render", "Render a scene (default: the built-in room) to PNG and/or EXR");
  render->add_option("scene", args.scene.scene, "Scene file (YAML); omitted: the built-in room");
  render->add_option("-o,--output", args.outputs,
                     "Output image, .png (8-bit colour) or .exr (R,G,B,A float, Z float, stencil uint32); "
                     "repeatable. Default: out/<scene>.png");
  render->add_option("--method", args.method, "Shadow method: " + shadowMethodNames());
  render->add_option("-D", args.scene.overrides, "Override a scene value, e.g. -D camera.near=0.001")
      ->take_all()
      ->allow_extra_args(false);
  render->add_option("--threads", args.threads, "Worker threads (0: all cores); the output does not depend on it")
      ->check(CLI::Range(0, 256));
  render->add_flag("--quiet", args.quiet, "Print nothing but errors");
  render->add_flag("--stats", args.stats, "Print triangle, fragment and stencil counts and time per pass");
  render->add_option("--dump", args.dumps, "Teaching dumps: 'passes' writes one image per pass")
      ->check(CLI::IsMember({"passes"}));
  render->add_option("--pixel-history", args.pixelHistory, "x,y: print every fragment that touched that pixel");
}

int runRender(const RenderArgs& args) {
  std::optional<Scene> scene = loadSceneOrReport(args.scene);
  if (!scene) return kBadInput;

  FrameOptions options;
  if (!args.method.empty()) {
    options.method = parseShadowMethod(args.method);
    if (!options.method) {
      std::cerr << "--method: unknown method '" << args.method << "' (expected one of " << shadowMethodNames() << ")\n";
      return kBadInput;
    }
  }
  std::vector<std::string> outputs = args.outputs;
  if (outputs.empty()) outputs.push_back(defaultOutputPath(args.scene.scene, ".png"));
  for (const std::string& out : outputs) {
    const std::string ext = std::filesystem::path(out).extension().string();
    if (ext != ".png" && ext != ".exr" && ext != ".PNG" && ext != ".EXR") {
      std::cerr << out << ": unsupported output format '" << ext << "' (expected .png or .exr)\n";
      return kBadInput;
    }
  }

  const std::vector<Instance> instances = scene->instances();
  PixelHistoryPrinter history(instances);
  if (!args.pixelHistory.empty()) {
    if (!parsePixel(args.pixelHistory, options.watchX, options.watchY) || options.watchX < 0 ||
        options.watchY < 0 || options.watchX >= scene->width || options.watchY >= scene->height) {
      std::cerr << "--pixel-history: expected x,y inside the " << scene->width << "x" << scene->height << " image, got '"
                << args.pixelHistory << "'\n";
      return kBadInput;
    }
    options.observer = &history;
  }
  const bool dumpPasses = std::find(args.dumps.begin(), args.dumps.end(), "passes") != args.dumps.end();
  std::vector<std::string> passFiles;
  try {
    if (dumpPasses) {
      options.onPass = [&](const std::string& pass, const Framebuffer& fb) {
        if (!fb.hasColor()) return;
        const std::string path = passPath(outputs.front(), pass);
        ensureParentDirectory(path);
        writePng(fb, path);
        passFiles.push_back(path);
      };
    }
    const FrameResult frame = renderFrame(*scene, options);
    for (const std::string& out : outputs) {
      ensureParentDirectory(out);
      writeImage(frame.framebuffer, out);
      if (!args.quiet) std::cerr << "wrote " << out << '\n';
    }
    if (!args.quiet)
      for (const std::string& p : passFiles) std::cerr << "wrote " << p << '\n';
    if (args.stats) printStats(frame);
  } catch (const std::exception& e) {
    std::cerr << "render: " << e.what() << '\n';
    return kFailed;
  }
  if (options.observer) {
    std::cout << "pixel " << options.watchX << "," << options.watchY << " (row 0 is the bottom): "
              << history.lines().size() << " fragments\n";
    for (const std::string& line : history.lines()) std::cout << "  " << line << '\n';
  }
  return kSuccess;
}

}  // namespace shadowref::cli
