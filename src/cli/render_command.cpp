#include "cli/render_command.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>

#include "cli/oracle_output.h"
#include "cli/render_metadata.h"
#include "cli/render_option_checks.h"
#include "image/image_writer.h"
#include "image/stencil_view.h"
#include "scene/animation.h"
#include "scene/checked_arithmetic.h"
#include "shadow/frame_renderer.h"
#include "shadow/scene_view.h"
#include "shadow/soft_lights.h"
#include "shadow/technique_registry.h"
#include "views/depth_view.h"
#include "views/pixel_history.h"
#include "views/stencil_counts_view.h"
#include "views/volume_colours.h"
#include "trace/trace_recorder.h"

namespace shadowref::cli {

namespace {

bool parsePixel(const std::string& text, int& x, int& y) {
  char comma = 0;
  std::istringstream in(text);
  return bool(in >> x >> comma >> y) && comma == ',' && in.peek() == EOF;
}

// "out/room.png" + "pass-01-ambient" -> "out/room.pass-01-ambient.png"
std::string siblingPath(const std::string& output, const std::string& suffix) {
  std::filesystem::path p(output);
  return (p.parent_path() / (p.stem().string() + "." + suffix + ".png")).string();
}

bool parseInts(const std::string& text, std::vector<int64_t>& values, size_t count) {
  values.clear();
  std::istringstream in(text);
  for (size_t i = 0; i < count; ++i) {
    int64_t v = 0;
    if (!(in >> v)) return false;
    values.push_back(v);
    if (i + 1 < count && in.get() != ',') return false;
  }
  return in.peek() == EOF;
}

std::string lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return text;
}

// True when a and b name the same file: the same inode if both exist, else the same normalised path.
bool sameFile(const std::string& a, const std::string& b) {
  std::error_code ec;
  if (std::filesystem::exists(a, ec) && std::filesystem::exists(b, ec))
    return std::filesystem::equivalent(a, b, ec);
  const std::filesystem::path ca = std::filesystem::weakly_canonical(a, ec);
  if (ec) return false;
  const std::filesystem::path cb = std::filesystem::weakly_canonical(b, ec);
  return !ec && ca == cb;
}

// The per-light stencil counts a render may keep for the stencil.L<i> channels of an EXR: each is a
// byte while rendering and 4 bytes twice while the EXR is written, so 2^27 of them take about
// 1.2 GiB (e.g. 8 lights at 4096 x 4096, or 2 at 8192 x 8192).
constexpr uint64_t kMaxKeptStencilCounts = uint64_t(1) << 27;

// The per-light visibility values a render may keep for --dump visibility: each a float while
// counting, again when finished and once more as an EXR channel, so 2^26 of them take about
// 1 GiB at most (e.g. 4 lights at 4096 x 4096, 64 at 1024 x 1024).
constexpr uint64_t kMaxVisibilityValues = uint64_t(1) << 26;

bool wants(const std::vector<std::string>& dumps, const char* what) {
  return std::find(dumps.begin(), dumps.end(), what) != dumps.end();
}

void writeOutput(const FrameResult& frame, const std::string& out, const ExrExtras& extras,
                 const OutputMetadata& metadata, std::vector<std::string>& madeFolders) {
  ensureParentDirectory(out, &madeFolders);
  const std::string ext = lowercase(std::filesystem::path(out).extension().string());
  if (ext == ".exr") writeExr(frame.framebuffer, out, extras, metadata);
  else writeImage(frame.framebuffer, out, metadata);
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
                     "repeatable; missing folders are made. Default: out/<scene>.png");
  render->add_option("--method", args.method, methodHelp());
  render->add_option("-D", args.scene.overrides, "Override a scene value, e.g. -D camera.near=0.001")
      ->take_all()
      ->allow_extra_args(false);
  render->add_option("--threads", args.threads, "Worker threads (0: one per CPU this process may run on, e.g. 1 under taskset -c 0); the output does not depend on it")
      ->check(wholeNumberIn(0, 256));
  render->add_option("--pipeline", args.pipeline,
                     "'fast' (default: the executor, threaded) or 'reference' (the readable GL pipeline, one thread); "
                     "both give the same bytes")
      ->check(CLI::IsMember({"reference", "fast"}));
  render->add_option("--exr-compression", args.exrCompression,
                     "Lossless compression of .exr outputs: 'rle' (default: fast, larger), 'zip' (smaller, about "
                     "five times the encoding time), 'none'")
      ->check(CLI::IsMember({"none", "rle", "zip"}));
  render->add_flag("--quiet", args.quiet, "Print nothing but errors (and no progress bar for --frames)");
  render->add_flag("--stats", args.stats, "Print triangle, fragment and stencil counts and time per pass");
  render->add_option("--dump", args.dumps,
                     "Teaching dumps, repeatable: 'passes' (one PNG per pass), 'stencil' (volume methods, per light: "
                     "false-colour PNG with legend, and stencil.L<i> EXR channels), 'depth' (eye depth on a colour map, "
                     "auto-ranged, with a colour bar), 'shadowmap' (map methods, per light: stored depth likewise, and "
                     "EXR with the Z channel), 'visibility' (per scene light: grey PNG, 1 lit white, 0 in shadow "
                     "black, and visibility.L<i> EXR channels, for every method)")
      ->check(CLI::IsMember({"passes", "stencil", "depth", "shadowmap", "visibility"}));
  render->add_flag("--oracle", args.oracle,
                   "Per light: the ray-traced visibility (OUT.oracle-L<i>.png) and an error map of the rendered one "
                   "against it (OUT.oracle-errors-L<i>.png); prints agreement and where they differ");
  render->add_option("--dump-region", args.dumpRegion, "x,y,w,h: print the stencil counts of that region per light "
                                                       "(row 0 is the bottom; volume methods)");
  render->add_option("--stencil-view", args.stencilView,
                     "How stencil counts read in --dump stencil/passes, --dump-region and --pixel-history: 'unsigned' "
                     "(default: the byte, 255 stays 255) or 'signed' (128..255 as -128..-1, for wrapping ops)")
      ->check(CLI::IsMember({"unsigned", "signed"}));
  render->add_option("--view", args.view,
                     "Draw the shadow volumes over the frame (volume methods): 'volumes' (front and back faces in two "
                     "hues per light, away from the scene's colours, [SV slides]) or 'volumes-overlay' (translucent "
                     "red, [DSS article])")
      ->check(CLI::IsMember({"volumes", "volumes-overlay"}));
  render->add_option("--pixel-history", args.pixelHistory,
                     "x,y: print every fragment that touched that pixel by pass and light, the clears, and each "
                     "shadow-map lookup (always rendered by the reference pipeline)");
  addSequenceOptions(*render, args.sequence);
  render->add_option("--capture", args.capture,
                     "Write the frame's commands (every clear, draw, accumulation, end of pass) and final buffers to "
                     "this trace file, for `shadowref replay` (docs/trace-format.md)");
}

int runRender(const RenderArgs& args) {
  std::optional<Scene> loaded = loadSceneOrReport(args.scene);
  if (!loaded) return kBadInput;
  if (wantsSequence(args.sequence)) return runFrameSequence(args, *loaded);
  if (loaded->animation) {
    try {
      loaded = sceneAt(*loaded, 0.0);  // a still of an animated scene is its frame 0
    } catch (const SceneError& e) {
      std::cerr << e.what() << '\n';
      return kBadInput;
    }
  }
  return renderScene(args, *loaded, FrameHooks{});
}

int renderScene(const RenderArgs& args, const Scene& sceneValue, const FrameHooks& hooks) {
  const Scene* scene = &sceneValue;

  // Every flag is checked here, before the render: bad usage exits 2 with nothing written.
  FrameOptions options;
  options.threads = args.threads;
  options.pipeline = args.pipeline == "reference" ? PipelineKind::Reference : PipelineKind::Fast;
  if (!checkMethodOrReport(args.method)) return kBadInput;
  options.method = args.method;
  const ShadowTechnique& technique = args.method.empty() ? techniqueOf(scene->shadow) : *findTechnique(args.method);
  if (const std::string problem = inapplicableRenderOption(args, technique); !problem.empty()) {
    std::cerr << problem << '\n';
    return kBadInput;
  }
  const bool signedCounts = args.stencilView == "signed";
  std::vector<std::string> outputs = hooks.outputs.empty() ? args.outputs : hooks.outputs;
  if (outputs.empty()) outputs.push_back(defaultOutputPath(args.scene.scene, ".png"));
  bool anyExr = false;
  for (const std::string& out : outputs) {
    // Any case, as writeImage accepts it: out.PNG, out.Exr.
    const std::string ext = lowercase(std::filesystem::path(out).extension().string());
    if (ext != ".png" && ext != ".exr") {
      std::cerr << out << ": unsupported output format '" << std::filesystem::path(out).extension().string()
                << "' (expected .png or .exr, in any case)\n";
      return kBadInput;
    }
    anyExr = anyExr || ext == ".exr";
    if (const std::string problem = outputFolderProblem(out); !problem.empty()) {
      std::cerr << out << ": " << problem << '\n';
      return kBadInput;
    }
    if (!args.scene.scene.empty() && sameFile(out, args.scene.scene)) {
      std::cerr << out << ": refusing to write the output over the scene file itself\n";
      return kBadInput;
    }
  }

  if (!args.capture.empty()) {
    if (!args.pixelHistory.empty()) {
      std::cerr << "--capture: cannot be combined with --pixel-history\n";
      return kBadInput;
    }
    if (const std::string problem = outputFolderProblem(args.capture); !problem.empty()) {
      std::cerr << args.capture << ": " << problem << '\n';
      return kBadInput;
    }
  }
  const std::vector<Instance> instances = scene->instances();
  std::optional<views::PixelHistory> history;
  if (!args.pixelHistory.empty()) {
    int x = -1, y = -1;
    if (!parsePixel(args.pixelHistory, x, y) || x < 0 || y < 0 || x >= scene->width || y >= scene->height) {
      std::cerr << "--pixel-history: expected x,y inside the " << scene->width << "x" << scene->height << " image, got '"
                << args.pixelHistory << "'\n";
      return kBadInput;
    }
    history.emplace(x, y);
    options.pipeline = PipelineKind::Reference;  // the pixel history's events are the reference's
  }
  const bool dumpPasses = wants(args.dumps, "passes");
  const bool dumpStencil = wants(args.dumps, "stencil");
  std::vector<int64_t> region;
  if (!args.dumpRegion.empty()) {
    // 64-bit ends: x + w cannot overflow for any x, w an int holds; the region must meet the image.
    const bool parsed = parseInts(args.dumpRegion, region, 4);
    const bool valid = parsed && region[2] > 0 && region[3] > 0 && region[2] <= INT32_MAX && region[3] <= INT32_MAX &&
                       region[0] >= INT32_MIN && region[1] >= INT32_MIN && region[0] < scene->width &&
                       region[1] < scene->height && region[0] + region[2] > 0 && region[1] + region[3] > 0;
    if (!valid) {
      std::cerr << "--dump-region: expected x,y,w,h (whole numbers, w and h at least 1) of a region that overlaps the "
                << scene->width << "x" << scene->height << " image, got '" << args.dumpRegion << "'\n";
      return kBadInput;
    }
  }
  // The per-light stencil PNGs and grids are made as each light's volume pass ends (below), so
  // they hold one light's buffer at a time. Only the stencil.L<i> channels of an EXR need every
  // light's counts at once: their number is bounded before anything is rendered.
  options.keepStencil = (dumpStencil || !region.empty()) && anyExr;
  if (options.keepStencil) {
    uint64_t lights = 0;
    for (const Light& light : scene->lights) lights += expandSoftLight(light).size();
    const std::optional<uint64_t> counts =
        checkedMul(checkedMul(uint64_t(scene->width), uint64_t(scene->height)).value_or(UINT64_MAX), lights);
    if (technique.countsInStencil && lights > 1 && (!counts || *counts > kMaxKeptStencilCounts)) {
      std::cerr << "--dump stencil with an .exr output: the EXR's per-light stencil channels would hold " << lights
                << " lights x " << scene->width << "x" << scene->height << " counts, more than the limit of "
                << kMaxKeptStencilCounts << " (2^27); drop the .exr output or the --dump, or render fewer lights or a "
                   "smaller image\n";
      return kBadInput;
    }
  }
  options.keepVisibility = wants(args.dumps, "visibility") || args.oracle;
  if (options.keepVisibility) {
    const std::optional<uint64_t> values = checkedMul(
        checkedMul(uint64_t(scene->width), uint64_t(scene->height)).value_or(UINT64_MAX), uint64_t(scene->lights.size()));
    if (!values || *values > kMaxVisibilityValues) {
      std::cerr << "--dump visibility: " << scene->lights.size() << " lights x " << scene->width << "x"
                << scene->height << " pixels is more than the limit of " << kMaxVisibilityValues
                << " (2^26) visibility values; render fewer lights (-D lights.NAME=off) or a smaller image\n";
      return kBadInput;
    }
  }
  options.keepShadowMaps = wants(args.dumps, "shadowmap");
  if (args.view == "volumes") {
    options.volumeView = VolumeViewMode::FrontBack;
    options.volumeColours = views::volumeColours(*scene);
  }
  if (args.view == "volumes-overlay") options.volumeView = VolumeViewMode::Overlay;
  std::vector<std::string> passFiles;
  std::vector<std::string> madeFolders;  // by this render: taken away again if it fails
  std::string grids;  // --dump-region's text, one grid per light, printed after the render
  try {
    OutputMetadata metadata = renderMetadata(args, *scene, options);
    metadata.extra.insert(metadata.extra.end(), hooks.metadata.begin(), hooks.metadata.end());
    const auto showing = [&](std::string content) {
      OutputMetadata m = metadata;
      m.content = std::move(content);
      return m;
    };
    options.onPass = [&](const std::string& pass, const Framebuffer& fb) {
      // "NN-stencil-L<i>": the counts of light i are in the stencil buffer now.
      const size_t at = pass.find("-stencil-");
      if (at != std::string::npos && fb.hasStencil() && (dumpStencil || !region.empty())) {
        const std::string light = pass.substr(at + 9);
        if (dumpStencil) {
          const std::string path = siblingPath(outputs.front(), "stencil-" + light);
          ensureParentDirectory(path, &madeFolders);
          views::writeViewPng(views::stencilView(fb.stencil(), fb.width(), fb.height(), {.signedCounts = signedCounts}),
                              path, showing("stencil " + light));
          passFiles.push_back(path);
        }
        if (!region.empty())
          grids += "light " + light + ":\n" +
                   stencilGrid(fb.stencil(), fb.width(), fb.height(), int(region[0]), int(region[1]), int(region[2]),
                               int(region[3]), signedCounts);
      }
      if (!dumpPasses) return;
      const std::string path = siblingPath(outputs.front(), "pass-" + pass);
      ensureParentDirectory(path, &madeFolders);
      // A volume pass changes only the stencil buffer: its picture is the stencil counts.
      if (pass.find("stencil") != std::string::npos && fb.hasStencil()) {
        views::writeViewPng(views::stencilView(fb.stencil(), fb.width(), fb.height(), {.signedCounts = signedCounts}),
                            path, showing("pass " + pass));
      } else if (fb.hasColor()) {
        writePng(fb, path, false, showing("pass " + pass));
      } else {
        return;
      }
      passFiles.push_back(path);
    };
    // --capture: the frame's pipelines record every command (src/trace/trace_recorder.h).
    std::unique_ptr<PipelineMaker> innerMaker, recordingMaker;
    std::unique_ptr<trace::TraceRecorder> recorder;
    if (!args.capture.empty()) {
      innerMaker = makePipelineMaker(options.pipeline, options.threads);
      recorder = std::make_unique<trace::TraceRecorder>();
      recordingMaker = recorder->wrap(*innerMaker);
      options.pipelines = recordingMaker.get();
    }
    if (history) history->attach(options);  // after onPass: its own is called first
    const FrameResult frame = renderFrame(*scene, options);
    if (recorder) {
      ensureParentDirectory(args.capture, &madeFolders);
      recorder->write(args.capture);
      if (!args.quiet) std::cerr << "wrote " << args.capture << '\n';
    }
    // The EXR's ZIP blocks compress on as many threads as a fast frame renders on (same bytes).
    if (anyExr || options.keepShadowMaps) setImageWriterThreads(pipelineThreads(PipelineKind::Fast, options.threads));
    setExrCompression(*exrCompressionNamed(args.exrCompression));
    if (!args.quiet)
      for (const std::string& warning : frame.warnings) std::cerr << "warning: " << warning << '\n';
    ExrExtras extras = perLightStencilChannels(frame.stencilPerLight, frame.stencilLightNames);
    OutputMetadata frameMetadata = showing("frame");
    // visibility.L<i>: light i of the scene, named in the header (shadowref:visibility.L<i>).
    for (size_t i = 0; i < frame.visibility.size(); ++i) {
      const std::string channel = "visibility.L" + std::to_string(i);
      extras.channels.push_back(NamedChannel::floatChannel(channel, frame.visibility[i]));
      frameMetadata.extra.emplace_back("shadowref:" + channel, scene->lights[i].name);
    }
    for (const std::string& out : outputs) {
      writeOutput(frame, out, extras, frameMetadata, madeFolders);
      if (!args.quiet && hooks.listWrites) std::cerr << "wrote " << out << '\n';
    }
    if (wants(args.dumps, "depth") && frame.framebuffer.hasDepth()) {
      std::vector<float> depth(frame.framebuffer.depthCodes().size());
      for (size_t i = 0; i < depth.size(); ++i) depth[i] = float(frame.framebuffer.depthCodec().decode(frame.framebuffer.depthCodes()[i]));
      const std::string path = siblingPath(outputs.front(), "depth");
      // The camera the technique drew with: volumes need P_inf ([Kuhn 2016, §3.3]).
      const SceneView camera = makeCameraView(*scene, technique.drawsVolumes);
      views::writeViewPng(views::depthView(depth, scene->width, scene->height, camera.projection, camera.viewport), path,
                          showing("depth"));
      passFiles.push_back(path);
    }
    for (size_t i = 0; i < frame.visibility.size(); ++i) {
      const std::string light = "L" + std::to_string(i);
      const std::string path = siblingPath(outputs.front(), "visibility-" + light);
      OutputMetadata m = showing("visibility " + light + " '" + scene->lights[i].name + "'");
      m.extra.emplace_back("shadowref:light", scene->lights[i].name);
      writeGreyPng(frame.visibility[i], scene->width, scene->height, path, 0.0f, 1.0f, m);
      passFiles.push_back(path);
    }
    for (size_t i = 0; i < frame.shadowMaps.size(); ++i) {
      const DepthTexture& map = frame.shadowMaps[i];
      const std::string png = siblingPath(outputs.front(), "shadowmap-" + frame.shadowMapNames[i]);
      const std::vector<float> depth = map.values();
      views::View picture = views::shadowMapView(depth, map.width, map.height);
      views::drawShadowMapOutline(picture, frame.shadowMapOutlines[i]);
      views::writeViewPng(picture, png, showing("shadow map " + frame.shadowMapNames[i]));
      Framebuffer holder(map.width, map.height);
      ExrExtras z;
      z.channels.push_back(NamedChannel::floatChannel("Z", depth));
      std::string exr = png.substr(0, png.size() - 4) + ".exr";
      writeExr(holder, exr, z, showing("shadow map " + frame.shadowMapNames[i]));
      passFiles.push_back(png);
      passFiles.push_back(exr);
    }
    if (args.oracle) {
      const std::string method = options.method.empty() ? std::string(techniqueOf(scene->shadow).name) : options.method;
      writeOracleOutputs(*scene, method, frame, [&](const std::string& s) { return siblingPath(outputs.front(), s); },
                         passFiles, std::cout);
    }
    std::cout << grids;
    if (hooks.onFrame) hooks.onFrame(frame.framebuffer);
    if (!args.quiet && hooks.listWrites)
      for (const std::string& p : passFiles) std::cerr << "wrote " << p << '\n';
    if (args.stats) printStats(frame);
  } catch (const std::exception& e) {
    removeEmptyFolders(madeFolders);
    std::cerr << "render: " << e.what() << '\n';
    return kFailed;
  }
  if (history) {
    std::vector<std::string> lightNames;  // L<i>: the lights as the passes number them, soft ones expanded
    for (const Light& light : scene->lights)
      for (const Light& l : expandSoftLight(light)) lightNames.push_back(l.name);
    std::cout << history->text(instances, lightNames, signedCounts);
  }
  return kSuccess;
}

}  // namespace shadowref::cli
