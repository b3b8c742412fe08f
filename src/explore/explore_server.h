// `shadowref explore`: the shadow lab in the browser. A local HTTP server whose page (built into
// the binary, src/explore/page/) orbits the camera, moves lights, switches methods and views and
// shows a pixel's history; every state is a list of `-D key=value` overrides, so the picture for
// a state is the picture `shadowref render` makes with the same -D values.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace shadowref::explore {

struct ExploreOptions {
  std::string scene;                   // empty: the built-in room
  std::vector<std::string> overrides;  // -D given to explore: the start of every state
  std::string host = "127.0.0.1";
  int port = 8080;                     // 0: any free port
  std::optional<int> threads;          // rasterizer threads, 0: every core; unset: serverThreads, or every
                                       // core for --export
  std::string exportDir;               // non-empty: write a self-contained page there and exit
};

// The server's rasterizer threads for `requested` (ExploreOptions::threads): unset, every core but
// one, at least one. The page's browser runs on the same machine and needs about a core of its
// own for a live frame rate (receiving, decoding and drawing 30 frames a second); a render that
// also takes that core waits for it in every pass (docs/performance.md).
int serverThreads(std::optional<int> requested);

// Serves until SIGINT or SIGTERM (exit status 0), printing the URL on stdout. 2 when the address
// cannot be bound.
int runExploreServer(const ExploreOptions& options);

// Writes the page with a set of views and their per-pixel values into options.exportDir, which must
// not exist or be empty; all or nothing (a temporary folder beside it is renamed at the end).
// 0 on success, 1 when writing fails, 2 for a scene that does not load, 130/143 after a signal.
int exportPage(const ExploreOptions& options);

// The page's embedded files (index.html, explore.js, explore.css); empty for an unknown name.
std::string_view pageFile(std::string_view name);

}  // namespace shadowref::explore
