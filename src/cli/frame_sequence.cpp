#include "cli/frame_sequence.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <functional>
#include <iostream>
#include <memory>
#include <spawn.h>
#include <sstream>
#include <stdexcept>
#include <sys/wait.h>
#include <unistd.h>

#include "cli/render_command.h"
#include "image/atomic_write.h"
#include "image/bitmap_font.h"
#include "image/image_writer.h"
#include "scene/animation.h"
#include "scene/resource_limits.h"

extern char** environ;

namespace shadowref::cli {

namespace {

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

bool parseFrameNumber(std::string_view text, int64_t& value) {
  if (text.empty() || text.size() > 18) return false;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && end == text.data() + text.size();
}

std::string formatNumber(double x, int precision = 6) {
  std::ostringstream out;
  out.precision(precision);
  out << x;
  return out.str();
}

// The full path of an executable found on PATH, or "" (what posix_spawnp would run).
std::string findOnPath(const std::string& name) {
  const char* path = std::getenv("PATH");
  if (!path) return "";
  std::istringstream dirs(path);
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    const std::string candidate = (dir.empty() ? std::string(".") : dir) + "/" + name;
    if (::access(candidate.c_str(), X_OK) == 0 && std::filesystem::is_regular_file(candidate)) return candidate;
  }
  return "";
}

// ---- ffmpeg ---------------------------------------------------------------------------------

// One ffmpeg process reading raw RGB frames on its standard input and writing one movie file.
// Its own messages (-loglevel error) go to our standard error.
class Encoder {
 public:
  Encoder(const std::string& ffmpeg, const std::vector<std::string>& args) {
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error(std::string("cannot make a pipe: ") + std::strerror(errno));
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, fds[0], 0);  // dup2 clears O_CLOEXEC on fd 0
    std::vector<std::string> argv{ffmpeg};
    argv.insert(argv.end(), args.begin(), args.end());
    std::vector<char*> cargv;
    for (std::string& a : argv) cargv.push_back(a.data());
    cargv.push_back(nullptr);
    const int rc = posix_spawn(&pid_, ffmpeg.c_str(), &actions, nullptr, cargv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    ::close(fds[0]);
    if (rc != 0) {
      ::close(fds[1]);
      throw std::runtime_error("cannot run " + ffmpeg + ": " + std::strerror(rc));
    }
    fd_ = fds[1];
  }
  Encoder(const Encoder&) = delete;
  Encoder& operator=(const Encoder&) = delete;
  ~Encoder() {
    // Only on failure: the movie is abandoned (its temporary file is removed by the caller).
    if (fd_ >= 0) ::close(fd_);
    if (pid_ > 0) {
      ::kill(pid_, SIGTERM);
      int status = 0;
      ::waitpid(pid_, &status, 0);
    }
  }

  void write(const Image8& frame) {
    const uint8_t* data = frame.pixels.data();
    size_t left = frame.pixels.size();
    while (left > 0) {
      const ssize_t n = ::write(fd_, data, left);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) throw std::runtime_error("ffmpeg stopped reading frames (its message is above)");
      data += n;
      left -= size_t(n);
    }
  }

  // Ends the input and waits; throws unless ffmpeg exited with status 0.
  void finish() {
    ::close(fd_);
    fd_ = -1;
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
    pid_ = -1;
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
      throw std::runtime_error("ffmpeg failed (exit status " + std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) +
                               "; its message is above)");
  }

 private:
  pid_t pid_ = -1;
  int fd_ = -1;
};

struct Movie {
  std::string path;  // the target
  bool gif = false;
  std::string temp;  // the temporary file ffmpeg writes, renamed over path when all is well
  std::unique_ptr<Encoder> encoder;
};

// The ffmpeg arguments for raw RGB frames of w x h at fps in, one movie out. Both formats are
// written with bit-exact flags (no encoder version or time in the file).
std::vector<std::string> ffmpegArgs(const Movie& m, int w, int h, double fps) {
  std::vector<std::string> a{"-hide_banner", "-nostdin", "-loglevel", "error", "-y",
                             "-f", "rawvideo", "-pix_fmt", "rgb24", "-video_size",
                             std::to_string(w) + "x" + std::to_string(h), "-framerate", formatNumber(fps, 10),
                             "-i", "pipe:0", "-fflags", "+bitexact", "-flags:v", "+bitexact"};
  if (m.gif) {
    // One palette for the whole animation from every frame, ordered dithering (no error diffusion
    // noise that changes from frame to frame), looping forever.
    a.insert(a.end(), {"-filter_complex", "[0:v]split[a][b];[a]palettegen=stats_mode=full[p];[b][p]paletteuse=dither=bayer:bayer_scale=5",
                       "-loop", "0", "-f", "gif"});
  } else {
    // H.264 in 4:2:0 needs even sides: an odd side gets one black row or column.
    a.insert(a.end(), {"-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v", "libx264", "-pix_fmt", "yuv420p", "-crf", "18",
                       "-threads", "1", "-f", "mp4"});
  }
  a.push_back(m.temp);
  return a;
}

// ---- contact sheet --------------------------------------------------------------------------

constexpr int kThumbSide = 192;  // a tile's longer side at most
constexpr int kLabelScale = 2;
constexpr int kGap = 4;

// The frame shrunk by a whole factor k (each tile pixel the rounded mean of a k x k box), so that
// its longer side is at most kThumbSide.
Image8 thumbnail(const Image8& frame) {
  const int k = (std::max(frame.width, frame.height) + kThumbSide - 1) / kThumbSide;
  Image8 t;
  t.width = std::max(1, frame.width / k);
  t.height = std::max(1, frame.height / k);
  t.channels = 3;
  t.pixels.assign(size_t(t.width) * size_t(t.height) * 3, 0);
  const unsigned area = unsigned(k * k);
  for (int y = 0; y < t.height; ++y)
    for (int x = 0; x < t.width; ++x)
      for (int c = 0; c < 3; ++c) {
        unsigned sum = 0;
        for (int dy = 0; dy < k && y * k + dy < frame.height; ++dy)
          for (int dx = 0; dx < k && x * k + dx < frame.width; ++dx)
            sum += frame.pixels[(size_t(y * k + dy) * size_t(frame.width) + size_t(x * k + dx)) * 3 + size_t(c)];
        t.pixels[(size_t(y) * size_t(t.width) + size_t(x)) * 3 + size_t(c)] = uint8_t((sum + area / 2) / area);
      }
  return t;
}

Image8 contactSheet(const std::vector<std::pair<int64_t, Image8>>& tiles) {
  const int n = int(tiles.size());
  const int cols = int(std::ceil(std::sqrt(double(n))));
  const int rows = (n + cols - 1) / cols;
  const int tw = tiles.front().second.width, th = tiles.front().second.height;
  const int label = kGlyphHeight * kLabelScale + 2 * kGap;
  Image8 sheet;
  sheet.width = kGap + cols * (tw + kGap);
  sheet.height = kGap + rows * (th + label);
  sheet.channels = 3;
  sheet.pixels.assign(size_t(sheet.width) * size_t(sheet.height) * 3, 40);
  for (int i = 0; i < n; ++i) {
    const int x0 = kGap + (i % cols) * (tw + kGap), y0 = kGap + (i / cols) * (th + label);
    const Image8& t = tiles[size_t(i)].second;
    for (int y = 0; y < th; ++y)
      std::memcpy(&sheet.pixels[(size_t(y0 + y) * size_t(sheet.width) + size_t(x0)) * 3],
                  &t.pixels[size_t(y) * size_t(tw) * 3], size_t(tw) * 3);
    drawText(sheet, x0, y0 + th + kGap, std::to_string(tiles[size_t(i)].first), kLabelScale, {255, 255, 255});
  }
  return sheet;
}

// ---- progress -------------------------------------------------------------------------------

// "frame 12/48 [######......] 25 %  0.21 s/frame  7.6 s left", redrawn in place; only on a terminal.
class Progress {
 public:
  Progress(bool enabled, int64_t total) : enabled_(enabled), total_(total) {}
  void update(int64_t done, double seconds) {
    if (!enabled_) return;
    constexpr int kWidth = 30;
    const int filled = int(done * kWidth / total_);
    const double perFrame = done > 0 ? seconds / double(done) : 0.0;
    std::fprintf(stderr, "\rframe %lld/%lld [%s%s] %3d %%  %.2f s/frame  %.1f s left   ", (long long)done,
                 (long long)total_, std::string(size_t(filled), '#').c_str(), std::string(size_t(kWidth - filled), '.').c_str(),
                 int(done * 100 / total_), perFrame, perFrame * double(total_ - done));
    std::fflush(stderr);
    drawn_ = true;
  }
  void end() {
    if (drawn_) std::fputc('\n', stderr);
    drawn_ = false;
  }

 private:
  bool enabled_;
  int64_t total_;
  bool drawn_ = false;
};

// Thrown inside the atomic writers to abandon the movies after a frame failed with this status.
struct FrameFailed {
  int status;
};

// Calls body() with a temporary file open for every movie (nested atomic writes): each movie is
// renamed into place only when body returns; any exception removes them all.
void withMovieFiles(std::vector<Movie>& movies, size_t i, const std::function<void()>& body) {
  if (i == movies.size()) return body();
  writeFileAtomically(movies[i].path, [&](const TempFile& temp) {
    movies[i].temp = temp.path;
    withMovieFiles(movies, i + 1, body);
  });
}

}  // namespace

void addSequenceOptions(CLI::App& render, SequenceArgs& args) {
  render.add_option("--frames", args.frames,
                    "A..B: render frames A to B of the scene's animation (frame n at t = n / fps s) into numbered "
                    "files, -o out/x.png -> out/x.0001.png; dumps are numbered the same way");
  render.add_option("--fps", args.fps, "Frames per second for --frames and the movie (default: the scene's animation.fps, "
                                       "else 24)");
  render.add_option("--gif", args.gif, "With --frames: also write an animated GIF of the frames (needs ffmpeg)");
  render.add_option("--mp4", args.mp4, "With --frames: also write an H.264 MP4 of the frames (needs ffmpeg)");
  render.add_option("--movie", args.movie, "With --frames: --gif or --mp4 by the file's extension");
  render.add_option("--contact-sheet", args.contactSheet,
                    "With --frames: also write a PNG of the frames in a grid, each labelled with its number (at most "
                    "64 tiles, evenly spaced)");
}

bool wantsSequence(const SequenceArgs& a) {
  return !a.frames.empty() || !a.fps.empty() || !a.gif.empty() || !a.mp4.empty() || !a.movie.empty() ||
         !a.contactSheet.empty();
}

std::optional<FrameRange> parseFrameRange(const std::string& text, std::string& error) {
  const std::string usage = "--frames: expected A..B, whole frame numbers from 0 to " + std::to_string(kMaxFrameNumber) +
                            " with A <= B (or one number N), got '" + text + "'";
  FrameRange r;
  const size_t dots = text.find("..");
  const std::string_view all(text);
  const bool parsed = dots == std::string::npos
                          ? parseFrameNumber(all, r.first) && (r.last = r.first, true)
                          : parseFrameNumber(all.substr(0, dots), r.first) && parseFrameNumber(all.substr(dots + 2), r.last);
  if (!parsed || r.first < 0 || r.last < 0 || r.first > kMaxFrameNumber || r.last > kMaxFrameNumber) {
    error = usage;
    return std::nullopt;
  }
  if (r.first > r.last) {
    error = "--frames: the range " + text + " is empty (A must not be greater than B)";
    return std::nullopt;
  }
  if (r.count() > kMaxSequenceFrames) {
    error = "--frames: " + text + " is " + std::to_string(r.count()) + " frames, more than the " +
            std::to_string(kMaxSequenceFrames) + " one command renders; split the range";
    return std::nullopt;
  }
  return r;
}

std::string numberedPath(const std::string& path, int64_t frame) {
  char number[24];
  std::snprintf(number, sizeof number, "%04lld", (long long)frame);
  const std::filesystem::path p(path);
  const std::string ext = p.extension().string();
  const std::string stem = p.stem().string() + "." + number + ext;
  return p.has_parent_path() ? (p.parent_path() / stem).string() : stem;
}

std::vector<int64_t> contactSheetFrames(int64_t count) {
  std::vector<int64_t> out;
  const int64_t tiles = std::min(count, kMaxContactTiles);
  if (tiles == 1) return {0};
  for (int64_t i = 0; i < tiles; ++i) out.push_back(i * (count - 1) / (tiles - 1));  // exact: integers
  return out;
}

int runFrameSequence(const RenderArgs& args, const Scene& scene) {
  const SequenceArgs& seq = args.sequence;
  // Every flag is checked before the first frame: bad usage exits 2 with nothing written.
  if (seq.frames.empty()) {
    std::cerr << "--fps, --gif, --mp4, --movie and --contact-sheet need --frames A..B\n";
    return kBadInput;
  }
  std::string error;
  const std::optional<FrameRange> range = parseFrameRange(seq.frames, error);
  if (!range) {
    std::cerr << error << '\n';
    return kBadInput;
  }
  double fps = scene.animation ? scene.animation->fps : 24.0;
  if (!seq.fps.empty()) {
    const auto [end, ec] = std::from_chars(seq.fps.data(), seq.fps.data() + seq.fps.size(), fps);
    if (ec != std::errc() || end != seq.fps.data() + seq.fps.size() || !(fps > 0.0 && fps <= kMaxAnimationFps)) {
      std::cerr << "--fps: expected a number of frames per second greater than 0 and at most " << kMaxAnimationFps
                << ", got '" << seq.fps << "'\n";
      return kBadInput;
    }
  }
  std::vector<Movie> movies;
  const auto addMovie = [&](const std::string& path, const char* flag, const std::string& want) -> bool {
    if (path.empty()) return true;
    const std::string ext = lowerExtension(path);
    if (ext != want && !(want.empty() && (ext == ".gif" || ext == ".mp4"))) {
      std::cerr << flag << " " << path << ": expected a file ending in "
                << (want.empty() ? std::string(".gif or .mp4") : want) << '\n';
      return false;
    }
    Movie m;
    m.path = path;
    m.gif = ext == ".gif";
    movies.push_back(std::move(m));
    return true;
  };
  if (!addMovie(seq.gif, "--gif", ".gif") || !addMovie(seq.mp4, "--mp4", ".mp4") || !addMovie(seq.movie, "--movie", ""))
    return kBadInput;
  if (!seq.contactSheet.empty() && lowerExtension(seq.contactSheet) != ".png") {
    std::cerr << "--contact-sheet " << seq.contactSheet << ": expected a file ending in .png\n";
    return kBadInput;
  }
  std::vector<std::string> extraFiles;
  for (const Movie& m : movies) extraFiles.push_back(m.path);
  if (!seq.contactSheet.empty()) extraFiles.push_back(seq.contactSheet);
  for (const std::string& f : extraFiles)
    if (const std::string problem = outputFolderProblem(f); !problem.empty()) {
      std::cerr << f << ": " << problem << '\n';
      return kBadInput;
    }
  std::string ffmpeg;
  if (!movies.empty()) {
    ffmpeg = findOnPath("ffmpeg");
    if (ffmpeg.empty()) {
      std::cerr << movies.front().path << ": an animated GIF or MP4 is assembled by ffmpeg, which is not on PATH "
                << "(Debian: apt-get install ffmpeg); the numbered frames and --contact-sheet need no ffmpeg\n";
      return kBadInput;
    }
  }

  // Every frame's scene is checked before the first is rendered (a camera that passes through its
  // target halfway is bad input like any other): exit 2 with nothing written. Evaluating costs a
  // copy of the scene graph per frame, little against rendering it.
  if (scene.animation) {
    try {
      for (int64_t n = range->first; n <= range->last; ++n) (void)sceneAt(scene, frameTime(n, fps));
    } catch (const SceneError& e) {
      std::cerr << e.what() << '\n';
      return kBadInput;
    }
  }

  std::vector<std::string> outputs = args.outputs;
  if (outputs.empty()) outputs.push_back(defaultOutputPath(args.scene.scene, ".png"));
  const std::vector<int64_t> sheetIndices = seq.contactSheet.empty() ? std::vector<int64_t>{} : contactSheetFrames(range->count());
  std::vector<std::pair<int64_t, Image8>> tiles;
  std::vector<std::string> madeFolders;
  Progress progress(!args.quiet && ::isatty(STDERR_FILENO), range->count());
  // A movie's ffmpeg may stop early; its message is what counts, not SIGPIPE.
  std::signal(SIGPIPE, SIG_IGN);
  const auto start = std::chrono::steady_clock::now();
  const auto seconds = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  int status = kSuccess;
  try {
    for (const std::string& f : extraFiles) ensureParentDirectory(f, &madeFolders);
    withMovieFiles(movies, 0, [&] {
      // On any failure the encoders stop before their temporary files are removed.
      struct StopEncoders {
        std::vector<Movie>& movies;
        ~StopEncoders() {
          for (Movie& m : movies) m.encoder.reset();
        }
      } stop{movies};
      size_t nextTile = 0;
      for (int64_t n = range->first; n <= range->last; ++n) {
        const double t = frameTime(n, fps);
        Scene frameScene;
        try {
          frameScene = sceneAt(scene, t);
        } catch (const SceneError& e) {
          progress.end();
          std::cerr << e.what() << '\n';
          throw FrameFailed{kBadInput};
        }
        FrameHooks hooks;
        for (const std::string& o : outputs) hooks.outputs.push_back(numberedPath(o, n));
        hooks.listWrites = false;
        hooks.metadata = {{"shadowref:frame", std::to_string(n)}, {"shadowref:time", formatNumber(t, 17)}};
        const int64_t index = n - range->first;
        hooks.onFrame = [&](const Framebuffer& fb) {
          if (movies.empty() && sheetIndices.empty()) return;
          const Image8 rgb = colorImage(fb);
          for (Movie& m : movies) {
            if (!m.encoder) m.encoder = std::make_unique<Encoder>(ffmpeg, ffmpegArgs(m, rgb.width, rgb.height, fps));
            m.encoder->write(rgb);
          }
          if (nextTile < sheetIndices.size() && sheetIndices[nextTile] == index) {
            tiles.emplace_back(n, thumbnail(rgb));
            ++nextTile;
          }
        };
        if (const int rc = renderScene(args, frameScene, hooks); rc != kSuccess) {
          progress.end();
          throw FrameFailed{rc};
        }
        progress.update(index + 1, seconds());
      }
      progress.end();
      for (Movie& m : movies) m.encoder->finish();
    });
    if (!tiles.empty()) {
      OutputMetadata metadata;
      metadata.content = "contact sheet, frames " + seq.frames;
      writePng8(contactSheet(tiles), seq.contactSheet, metadata);
    }
  } catch (const FrameFailed& f) {
    status = f.status;
  } catch (const std::exception& e) {
    progress.end();
    std::cerr << "render: " << e.what() << '\n';
    status = kFailed;
  }
  movies.clear();  // ends any ffmpeg still running
  if (status != kSuccess) {
    removeEmptyFolders(madeFolders);
    return status;
  }
  if (!args.quiet) {
    for (const std::string& o : outputs)
      std::cerr << "wrote " << range->count() << " frame" << (range->count() == 1 ? "" : "s") << ": "
                << numberedPath(o, range->first) << (range->count() > 1 ? " to " + numberedPath(o, range->last) : "") << '\n';
    for (const std::string& f : extraFiles) std::cerr << "wrote " << f << '\n';
    std::fprintf(stderr, "%lld frame%s at %s fps (t = %s to %s s) in %.2f s, %.3f s per frame\n",
                 (long long)range->count(), range->count() == 1 ? "" : "s", formatNumber(fps).c_str(), formatNumber(frameTime(range->first, fps)).c_str(),
                 formatNumber(frameTime(range->last, fps)).c_str(), seconds(), seconds() / double(range->count()));
    if (!scene.animation) std::cerr << "note: the scene has no animation section: every frame is the same\n";
  }
  return kSuccess;
}

}  // namespace shadowref::cli
