// `shadowref explore SCENE --export DIR`: the page without a server, for handouts.
#include <nettle/base64.h>
#include <pthread.h>
#include <signal.h>

#include <filesystem>
#include <iostream>
#include <unistd.h>

#include "explore/explore_server.h"
#include "explore/views_adapter.h"
#include "image/atomic_write.h"
#include "image/image_writer.h"
#include "scene/scene_error.h"
#include "scene/scene_loader.h"
#include "shadow/technique_registry.h"

namespace shadowref::explore {

namespace {

namespace fs = std::filesystem;

std::string base64(const void* data, size_t size) {
  std::string out(BASE64_ENCODE_RAW_LENGTH(size), '\0');
  base64_encode_raw(reinterpret_cast<char*>(out.data()), size, static_cast<const uint8_t*>(data));
  return out;
}

void writeText(const fs::path& path, std::string_view text) {
  writeFileAtomically(path.string(), [&](const TempFile& temp) { writeAllAt(temp.fd, text.data(), text.size(), 0); });
}

// A signal that arrived while exporting (0: none): SIGINT and SIGTERM are held back while the
// folder is written and checked between views, so that the temporary folder is always removed.
int pendingSignal(const sigset_t& set) {
  const timespec none{0, 0};
  const int sig = sigtimedwait(&set, nullptr, &none);
  return sig > 0 ? sig : 0;
}

}  // namespace

int exportPage(const ExploreOptions& options) {
  const fs::path target = fs::path(options.exportDir).lexically_normal();
  std::error_code ec;
  if (fs::exists(target, ec) && !(fs::is_directory(target, ec) && fs::is_empty(target, ec))) {
    std::cerr << "explore --export: " << target.string() << " exists and is not an empty folder\n";
    return 2;
  }
  Scene scene;
  try {
    LoadOptions load;
    load.overrides = options.overrides;
    scene = options.scene.empty() ? loadSceneFromString("generator: {type: room}\nshadow: {method: zfail}\n",
                                                         "<builtin:room>", load)
                                  : loadScene(options.scene, load);
    techniqueOf(scene.shadow);
  } catch (const SceneError& e) {
    std::cerr << e.what() << '\n';
    return 2;
  }
  const fs::path parent = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  if (!fs::is_directory(parent, ec)) {
    std::cerr << "explore --export: the folder " << parent.string() << " does not exist\n";
    return 2;
  }
  const fs::path temp = parent / (target.filename().string() + ".tmp-" + std::to_string(::getpid()));
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  sigset_t old;
  pthread_sigmask(SIG_BLOCK, &set, &old);
  int status = 0;
  try {
    fs::create_directory(temp);
    std::unique_ptr<PipelineMaker> pipelines = makePipelineMaker(PipelineKind::Fast, options.threads.value_or(0));
    const bool counts = techniqueOf(scene.shadow).countsInStencil;
    struct Entry {
      std::string id, label;
      ViewRequest request;
    };
    // The frame tells how many lights, maps and passes there are.
    const ViewImage first = renderView(scene, {View::Frame, 0, false}, *pipelines);
    std::vector<Entry> entries{{"frame", "frame", {View::Frame, 0, false}}, {"depth", "depth", {View::Depth, 0, false}}};
    const std::vector<std::string> passes = first.info["passes"].get<std::vector<std::string>>();
    if (counts) {
      entries.push_back({"volumes", "volumes", {View::Volumes, 0, false}});
      entries.push_back({"overlay", "translucent volumes", {View::Overlay, 0, false}});
      int light = 0;
      for (const std::string& pass : passes)
        if (pass.find("-stencil-") != std::string::npos) {
          entries.push_back({"stencil-" + std::to_string(light), "stencil " + pass.substr(pass.find("-stencil-") + 9),
                             {View::Stencil, light, false}});
          ++light;
        }
    } else if (scene.shadow.method != "none") {
      const ViewImage maps = renderView(scene, {View::ShadowMap, 0, false}, *pipelines);
      const std::vector<std::string> names = maps.info["shadowMaps"].get<std::vector<std::string>>();
      for (size_t m = 0; m < names.size(); ++m)
        entries.push_back({"shadowmap-" + std::to_string(m), "shadow map " + names[m], {View::ShadowMap, int(m), false}});
    }
    for (size_t l = 0; l < scene.lights.size(); ++l)
      entries.push_back({"visibility-" + std::to_string(l), "visibility " + scene.lights[l].name,
                         {View::Visibility, int(l), false}});
    for (size_t p = 0; p < passes.size(); ++p)
      entries.push_back({"pass-" + std::to_string(p), "pass " + passes[p], {View::Pass, int(p), false}});
    nlohmann::json views = nlohmann::json::array();
    std::string values;  // "SHADOWREF_VALUES['id'] = '<base64>';" lines
    for (const Entry& e : entries) {
      if (const int sig = pendingSignal(set)) {
        status = 128 + sig;
        break;
      }
      const ViewImage image = renderView(scene, e.request, *pipelines);
      Image8 png;
      png.width = image.width, png.height = image.height, png.channels = 3;
      png.pixels.resize(size_t(png.width) * size_t(png.height) * 3);
      for (size_t p = 0; p < size_t(png.width) * size_t(png.height); ++p)
        for (int k = 0; k < 3; ++k) png.pixels[p * 3 + size_t(k)] = image.rgba[p * 4 + size_t(k)];
      writePng8(png, (temp / (e.id + ".png")).string());
      nlohmann::json v{{"id", e.id}, {"label", e.label}, {"values", image.valueName},
                       {"width", image.width}, {"height", image.height}, {"info", image.info}};
      views.push_back(v);
      if (!image.values.empty())
        values += "SHADOWREF_VALUES['" + e.id + "'] = '" + base64(image.values.data(), image.values.size() * 4) + "';\n";
    }
    if (status == 0) {
      nlohmann::json data;
      data["scene"] = sceneSummary(scene);
      data["views"] = views;
      data["overrides"] = options.overrides;
      std::string js = "window.SHADOWREF_EXPORT = " + data.dump(-1, ' ', true) + ";\nwindow.SHADOWREF_VALUES = {};\n" +
                       "var SHADOWREF_VALUES = window.SHADOWREF_VALUES;\n" + values;
      writeText(temp / "data.js", js);
      std::string html(pageFile("index.html"));
      // The exported page loads its data before the page's script, which then runs without a server.
      const std::string marker = "<script src=\"explore.js\"></script>";
      const size_t at = html.find(marker);
      if (at != std::string::npos) html.insert(at, "<script src=\"data.js\"></script>\n");
      writeText(temp / "index.html", html);
      writeText(temp / "explore.js", pageFile("explore.js"));
      writeText(temp / "explore.css", pageFile("explore.css"));
      if (const int sig = pendingSignal(set)) status = 128 + sig;
    }
    if (status == 0) {
      if (fs::exists(target, ec)) fs::remove(target);  // the empty folder checked above
      fs::rename(temp, target);
      std::cerr << "wrote " << target.string() << "/index.html\n";
    }
  } catch (const std::exception& e) {
    std::cerr << "explore --export: " << e.what() << '\n';
    status = 1;
  }
  if (status != 0) fs::remove_all(temp, ec);
  pthread_sigmask(SIG_SETMASK, &old, nullptr);
  return status;
}

}  // namespace shadowref::explore
