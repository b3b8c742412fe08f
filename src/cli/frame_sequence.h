// `shadowref render SCENE --frames A..B`: the frames of an animated scene (scene/animation.h)
// rendered in one process into numbered files, with an optional animated GIF or MP4 (assembled
// by ffmpeg) and a contact sheet.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "scene/scene.h"

namespace CLI {
class App;
}

namespace shadowref::cli {

struct RenderArgs;

struct SequenceArgs {
  std::string frames;        // "A..B" (or "N"); empty: a still
  std::string fps;           // empty: the scene's animation.fps (text: "0" and "abc" are errors)
  std::string gif, mp4;      // animated GIF / MP4 of the frames
  std::string movie;         // the same, the format by the extension (.gif or .mp4)
  std::string contactSheet;  // PNG: the frames in a grid, each labelled with its number
};

void addSequenceOptions(CLI::App& render, SequenceArgs& args);

// True when any sequence flag is given: the render is then a sequence (or a usage error).
bool wantsSequence(const SequenceArgs& args);

struct FrameRange {
  int64_t first = 0, last = 0;  // inclusive, 0 <= first <= last <= kMaxFrameNumber
  int64_t count() const { return last - first + 1; }
};

// "A..B" or "N" (= N..N): whole numbers 0 … kMaxFrameNumber, A <= B, at most kMaxSequenceFrames
// frames (scene/resource_limits.h). On failure returns nullopt and sets `error` to the message.
std::optional<FrameRange> parseFrameRange(const std::string& text, std::string& error);

// "out/room.png", 7 -> "out/room.0007.png": the frame number zero-padded to at least 4 digits,
// before the extension (the last one, any case). A path without an extension gets ".NNNN" appended.
std::string numberedPath(const std::string& path, int64_t frame);

// The frames' times: frame n shows t = n / fps seconds.
inline double frameTime(int64_t frame, double fps) { return double(frame) / fps; }

// The tiles of a contact sheet of `count` frames: all of them up to kMaxContactTiles, else that
// many evenly spaced, the first and the last included (indices into the range, increasing).
inline constexpr int64_t kMaxContactTiles = 64;
std::vector<int64_t> contactSheetFrames(int64_t count);

// Renders the sequence; `scene` as loaded (with its animation, or a still scene: every frame is
// the same then). Exit status as runRender's.
int runFrameSequence(const RenderArgs& args, const Scene& scene);

}  // namespace shadowref::cli
