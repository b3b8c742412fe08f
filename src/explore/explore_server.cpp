#include "explore/explore_server.h"

#include <httplib.h>
#include <pthread.h>
#include <signal.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <deque>
#include <future>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <mutex>
#include <thread>

#include "explore/explore_request.h"
#include "explore/png_stream.h"
#include "explore/scene_save.h"
#include "explore/views_adapter.h"
#include "image/image_writer.h"
#include "memory/allocator_tuning.h"
#include "scene/input_file.h"
#include "scene/scene_error.h"
#include "scene/scene_loader.h"
#include "scene/scene_overrides.h"
#include "scene/scene_validation.h"
#include "shadow/technique_registry.h"

namespace shadowref::explore {

namespace {

// The built-in default scene, as `shadowref render` builds it without a scene file (the room of
// [Kuhn 2016, Fig. 5.1] with z-fail volumes).
constexpr const char* kBuiltinRoom = "generator: {type: room}\nshadow: {method: zfail}\n";
constexpr const char* kBuiltinName = "<builtin:room>";

// The largest picture a request may ask for (-D image.width/height): 16 Mpixel, 4096 x 4096.
constexpr uint64_t kMaxPixels = uint64_t(4096) * 4096;

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Refused with a reason: a 400 (a problem with the request, the message says what).
struct BadRequest : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The scenes and pipelines of the server. Rendering is one request at a time (each frame already
// uses every core); the last scene loaded is kept, so that a history or a view of the state just
// shown loads nothing.
class Explorer {
 public:
  explicit Explorer(const ExploreOptions& options)
      : options_(options), pipelines_(makePipelineMaker(PipelineKind::Fast, serverThreads(options.threads))) {}

  ~Explorer() {
    {
      std::lock_guard lock(queueLock_);
      stopping_ = true;
    }
    queued_.notify_one();
    if (renderer_.joinable()) renderer_.join();
  }

  // Runs `job` on the one render thread and waits for it, rethrowing what it throws. One thread
  // renders every frame: one request at a time (each frame already uses every core), and the
  // memory a frame frees stays with the thread that allocates the next (glibc keeps an arena per
  // thread), so that consecutive frames reuse their buffers instead of faulting in fresh pages.
  template <class F>
  void onRenderThread(F&& job) {
    std::packaged_task<void()> task(std::forward<F>(job));
    std::future<void> done = task.get_future();
    {
      std::lock_guard lock(queueLock_);
      if (!renderer_.joinable()) renderer_ = std::thread([this] { renderLoop(); });
      queue_.push_back(&task);
    }
    queued_.notify_one();
    done.get();
  }
  const PipelineMaker& pipelines() const { return *pipelines_; }

  // The scene for the explore command's -D followed by the request's; a SceneError is a bad request
  // (the message is its file:line:col). Call on the render thread.
  std::shared_ptr<const Scene> scene(const std::vector<std::string>& requestOverrides) {
    std::vector<std::string> all = options_.overrides;
    all.insert(all.end(), requestOverrides.begin(), requestOverrides.end());
    std::string key;
    for (const std::string& o : all) key += o + '\n';
    if (cached_ && key == cachedKey_) return cached_;
    std::optional<Scene> made = quickScene(requestOverrides);
    if (!made) {
      LoadOptions load;
      load.overrides = all;
      try {
        made = options_.scene.empty() ? loadSceneFromString(kBuiltinRoom, kBuiltinName, load)
                                      : loadScene(options_.scene, load);
        techniqueOf(made->shadow);
      } catch (const SceneError& e) {
        throw BadRequest(e.what());
      }
    }
    if (uint64_t(made->width) * uint64_t(made->height) > kMaxPixels)
      throw BadRequest("image " + std::to_string(made->width) + "x" + std::to_string(made->height) +
                       ": the explorer shows at most 4096 x 4096 pixels");
    cached_ = std::make_shared<const Scene>(std::move(*made));
    cachedKey_ = key;
    return cached_;
  }

  // The scene file's text, for save.
  std::string sourceText() const {
    if (options_.scene.empty()) return kBuiltinRoom;
    return readInputFile(options_.scene, "scene file", kMaxSceneFileBytes);
  }
  std::string sourceName() const { return options_.scene.empty() ? kBuiltinName : options_.scene; }
  const std::vector<std::string>& baseOverrides() const { return options_.overrides; }

  // The newest frame request: an older one still waiting for the render thread is not rendered.
  std::atomic<uint64_t> latestFrame{0};

 private:
  // What orbiting and dragging a light change: camera.KEY, shadow.KEY and lights.NAME.KEY. Applied
  // to a copy of the scene as the explore command's -D made it, they give the scene a full load
  // gives (the loader applies them after everything else, in order, and checks the result; a named
  // light is the same light before and after any removal), without running the generator and
  // reading the meshes again. Anything else, or any failure, goes through the full load, whose
  // message is the one the command line would print.
  static bool isQuick(const std::string& text) {
    const size_t eq = text.find('=');
    const std::string key = text.substr(0, eq);
    if (eq == std::string::npos) return false;
    if ((key.starts_with("camera.") || key.starts_with("shadow.")) && key.find('.', 7) == std::string::npos) return true;
    if (!key.starts_with("lights.")) return false;
    const size_t dot = key.find('.', 7);
    if (dot == std::string::npos || dot == 7) return false;  // lights.NAME=off: a removal
    const std::string name = key.substr(7, dot - 7);
    return name.find_first_not_of("0123456789") != std::string::npos;  // by name, not by number
  }

  std::optional<Scene> quickScene(const std::vector<std::string>& requestOverrides) {
    for (const std::string& o : requestOverrides)
      if (!isQuick(o)) return std::nullopt;
    try {
      if (!base_) {
        LoadOptions load;
        load.overrides = options_.overrides;
        base_ = std::make_shared<const Scene>(options_.scene.empty() ? loadSceneFromString(kBuiltinRoom, kBuiltinName, load)
                                                                     : loadScene(options_.scene, load));
      }
      Scene scene = *base_;
      ResourceLimits limits;
      Provenance where{SourceLocation{kCommandLineFile, 0, 0}};
      Removals removed;
      for (const Override& o : parseOverrides(requestOverrides)) applyOverride(o, scene, limits, where, removed);
      if (!removed.lights.empty() || !removed.nodes.empty()) return std::nullopt;
      validateScene(scene, limits, where);
      techniqueOf(scene.shadow);
      return scene;
    } catch (const std::exception&) {
      return std::nullopt;
    }
  }

  const ExploreOptions& options_;
  std::shared_ptr<const Scene> base_;  // the scene with the explore command's -D
  std::unique_ptr<PipelineMaker> pipelines_;
  void renderLoop() {
    for (;;) {
      std::packaged_task<void()>* task = nullptr;
      {
        std::unique_lock lock(queueLock_);
        queued_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
        if (queue_.empty()) return;
        task = queue_.front();
        queue_.pop_front();
      }
      (*task)();
    }
  }

  std::mutex queueLock_;
  std::condition_variable queued_;
  std::deque<std::packaged_task<void()>*> queue_;
  bool stopping_ = false;
  std::thread renderer_;
  std::shared_ptr<const Scene> cached_;
  std::string cachedKey_;
};

QueryParams paramsOf(const httplib::Request& req) { return QueryParams(req.params.begin(), req.params.end()); }

ExploreRequest parsed(const httplib::Request& req, const std::vector<std::string>& allowed) {
  ExploreRequest r;
  if (const std::optional<std::string> problem = parseRequest(paramsOf(req), allowed, r)) throw BadRequest(*problem);
  return r;
}

void checkPixel(const ExploreRequest& r, const Scene& scene) {
  if (r.x < 0 || r.y < 0) throw BadRequest("x and y are required");
  if (r.x >= scene.width || r.y >= scene.height)
    throw BadRequest("pixel " + std::to_string(r.x) + "," + std::to_string(r.y) + " is outside the " +
                     std::to_string(scene.width) + "x" + std::to_string(scene.height) + " image");
}

// Runs a handler, turning what it throws into the answer: 400 with the message for a bad request
// (bad parameters, a scene or override that does not load, a view the method does not have), 500
// for anything else. Nothing a request does ends the server.
template <class F>
void answer(httplib::Response& res, F&& handler) {
  try {
    handler();
  } catch (const BadRequest& e) {
    res.status = 400;
    res.set_content(e.what(), "text/plain; charset=utf-8");
  } catch (const std::invalid_argument& e) {
    res.status = 400;
    res.set_content(e.what(), "text/plain; charset=utf-8");
  } catch (const std::runtime_error& e) {
    res.status = 400;
    res.set_content(e.what(), "text/plain; charset=utf-8");
  } catch (const std::exception& e) {
    res.status = 500;
    res.set_content(std::string("internal error: ") + e.what(), "text/plain; charset=utf-8");
  }
}

void servePage(httplib::Server& server) {
  const std::pair<const char*, const char*> files[] = {
      {"/", "index.html"}, {"/explore.js", "explore.js"}, {"/explore.css", "explore.css"}};
  for (const auto& [route, file] : files) {
    const std::string name = file;
    const std::string type = name.ends_with(".html") ? "text/html; charset=utf-8"
                             : name.ends_with(".js") ? "text/javascript; charset=utf-8"
                                                     : "text/css; charset=utf-8";
    server.Get(route, [name, type](const httplib::Request&, httplib::Response& res) {
      const std::string_view body = pageFile(name);
      res.set_content(body.data(), body.size(), type.c_str());
    });
  }
}

void addRoutes(httplib::Server& server, Explorer& explorer) {
  servePage(server);
  // The scene's values for the controls. A scene that does not load is not an error of the
  // request: the page shows its file:line:col message.
  server.Get("/api/scene", [&](const httplib::Request& req, httplib::Response& res) {
    answer(res, [&] {
      const ExploreRequest r = parsed(req, {"D"});
      explorer.onRenderThread([&] {
        nlohmann::json out;
        try {
          out = sceneSummary(*explorer.scene(r.overrides));
        } catch (const BadRequest& e) {
          if (!r.overrides.empty()) throw;
          out["error"] = e.what();
        }
        out["baseOverrides"] = explorer.baseOverrides();
        res.set_content(out.dump(), "application/json");
      });
    });
  });
  // One view: a PNG (encoding=png, views without values), or raw bytes: RGBA, top row first, then
  // (X-Values) one float32 per pixel.
  server.Get("/api/frame", [&](const httplib::Request& req, httplib::Response& res) {
    answer(res, [&] {
      const ExploreRequest r = parsed(req, {"D", "view", "index", "signed", "seq", "encoding"});
      const uint64_t ticket = ++explorer.latestFrame;
      // Rendered on the render thread, encoded on this one: the render thread starts the next
      // frame (the page keeps a second request waiting) while this one is encoded and sent.
      ViewImage image;
      bool superseded = false;
      double loadMs = 0, renderMs = 0;
      explorer.onRenderThread([&] {
        if (ticket != explorer.latestFrame.load()) {  // a newer state came in while this one waited
          superseded = true;
          return;
        }
        const Clock::time_point start = Clock::now();
        const std::shared_ptr<const Scene> scene = explorer.scene(r.overrides);
        loadMs = msSince(start);
        image = renderView(*scene, r.view, explorer.pipelines());
        renderMs = msSince(start) - loadMs;
      });
      if (superseded) {
        res.status = 204;
        res.set_header("X-Superseded", "1");
        return;
      }
      const Clock::time_point encodeStart = Clock::now();
      // encoding=png: a picture without per-pixel values travels as PNG (lossless, a fraction of
      // the bytes; see png_stream.h); otherwise, and always with values, as raw RGBA + floats.
      const bool png = r.png && image.values.empty();
      std::string body = png ? encodePngRgb(image.rgba, image.width, image.height)
                             : std::string(reinterpret_cast<const char*>(image.rgba.data()), image.rgba.size());
      if (!image.values.empty())
        body.append(reinterpret_cast<const char*>(image.values.data()), image.values.size() * sizeof(float));
      const double encodeMs = msSince(encodeStart);
      res.set_header("X-Encode-Ms", std::to_string(encodeMs));
      res.set_header("X-Width", std::to_string(image.width));
      res.set_header("X-Height", std::to_string(image.height));
      res.set_header("X-Values", image.values.empty() ? "" : image.valueName);
      res.set_header("X-Info", image.info.dump(-1, ' ', true));
      res.set_header("X-Load-Ms", std::to_string(loadMs));
      res.set_header("X-Render-Ms", std::to_string(renderMs));
      res.set_header("X-Threads", std::to_string(explorer.pipelines().threads()));
      if (const auto it = req.params.find("seq"); it != req.params.end()) res.set_header("X-Seq", it->second);
      res.set_header("Cache-Control", "no-store");
      res.set_content(std::move(body), png ? "image/png" : "application/octet-stream");
    });
  });
  server.Get("/api/history", [&](const httplib::Request& req, httplib::Response& res) {
    answer(res, [&] {
      const ExploreRequest r = parsed(req, {"D", "x", "y", "signed"});
      explorer.onRenderThread([&] {
        const std::shared_ptr<const Scene> scene = explorer.scene(r.overrides);
        checkPixel(r, *scene);
        res.set_content(pixelHistory(*scene, r.x, r.y, r.view.signedCounts).dump(), "application/json");
      });
    });
  });
  server.Get("/api/stats", [&](const httplib::Request& req, httplib::Response& res) {
    answer(res, [&] {
      const ExploreRequest r = parsed(req, {"D"});
      explorer.onRenderThread([&] {
        res.set_content(frameStatistics(*explorer.scene(r.overrides), explorer.pipelines()).dump(), "application/json");
      });
    });
  });
  // The scene file with the state written in: checked by loading the state first.
  server.Get("/api/save", [&](const httplib::Request& req, httplib::Response& res) {
    answer(res, [&] {
      const ExploreRequest r = parsed(req, {"D"});
      explorer.onRenderThread([&] {
        const std::shared_ptr<const Scene> scene = explorer.scene(r.overrides);
        std::vector<std::string> names;
        for (const Light& l : scene->lights) names.push_back(l.name);
        std::vector<std::string> all = explorer.baseOverrides();
        all.insert(all.end(), r.overrides.begin(), r.overrides.end());
        res.set_content(sceneWithOverrides(explorer.sourceText(), all, names, explorer.sourceName()),
                        "text/yaml; charset=utf-8");
        res.set_header("Content-Disposition", "attachment; filename=\"explore-state.yaml\"");
      });
    });
  });
  server.set_exception_handler([](const httplib::Request&, httplib::Response& res, std::exception_ptr) {
    res.status = 500;
    res.set_content("internal error", "text/plain");
  });
}

// SIGINT and SIGTERM are blocked in every thread and taken by one that waits for them, so that the
// server is stopped from an ordinary thread (server.stop() is not async-signal-safe).
class SignalStop {
 public:
  SignalStop() {
    sigemptyset(&set_);
    sigaddset(&set_, SIGINT);
    sigaddset(&set_, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &set_, &old_);
  }
  ~SignalStop() {
    done_ = true;
    if (waiter_.joinable()) waiter_.join();
    pthread_sigmask(SIG_SETMASK, &old_, nullptr);
  }
  // Calls onSignal once SIGINT or SIGTERM arrives.
  template <class F>
  void start(F onSignal) {
    waiter_ = std::thread([this, onSignal] {
      const timespec tick{0, 100 * 1000 * 1000};
      while (!done_) {
        const int sig = sigtimedwait(&set_, nullptr, &tick);
        if (sig == SIGINT || sig == SIGTERM) {
          signal_ = sig;
          onSignal();
          return;
        }
      }
    });
  }
  int signal() const { return signal_; }

 private:
  sigset_t set_{}, old_{};
  std::thread waiter_;
  std::atomic<bool> done_{false};
  std::atomic<int> signal_{0};
};

}  // namespace

int serverThreads(std::optional<int> requested) {
  return requested.value_or(std::max(1, pipelineThreads(PipelineKind::Fast, 0) - 1));
}

int runExploreServer(const ExploreOptions& options) {
  SignalStop stop;  // before any thread starts, so every thread inherits the mask
  keepFreedMemoryForReuse();  // frame after frame: freed buffers are reused, not faulted in anew
  Explorer explorer(options);
  httplib::Server server;
  server.set_keep_alive_max_count(1000000);
  server.set_payload_max_length(1 << 16);
  // An answer is written as its headers and then its body. With Nagle's algorithm the body waits
  // for the headers' acknowledgement, which the browser delays (up to 40 ms on Linux): a frame
  // arrived 45 ms after it was encoded.
  server.set_tcp_nodelay(true);
  addRoutes(server, explorer);
  int port = options.port;
  if (port == 0) {
    port = server.bind_to_any_port(options.host);
    if (port < 0) {
      std::cerr << "explore: cannot listen on " << options.host << '\n';
      return 2;
    }
  } else if (!server.bind_to_port(options.host, port)) {
    std::cerr << "explore: cannot listen on " << options.host << ":" << port << " (in use, or not an address of this machine)\n";
    return 2;
  }
  // Whether the scene loads is shown on the page, not here: the page is where its message is read.
  std::cout << "shadowref explore: http://" << (options.host.find(':') != std::string::npos ? "[" + options.host + "]" : options.host)
            << ":" << port << "/  (Ctrl-C stops it)" << std::endl;
  stop.start([&] { server.stop(); });
  server.listen_after_bind();
  std::cout << "shadowref explore: stopped" << std::endl;
  return 0;
}

}  // namespace shadowref::explore
