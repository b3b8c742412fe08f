// Provenance carried by every image shadowref writes: which program made it, from which scene and
// with which settings. Written as header attributes (EXR) and tEXt chunks (PNG); see
// docs/outputs.md for the fields. Every field is a function of the inputs alone (no time stamp,
// no host name), so the same render gives the same file bytes.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace shadowref {

struct OutputMetadata {
  std::string software;                // "shadowref 0.1.0 (78535ab)"; empty: the file carries no metadata
  std::string content;                 // what this file shows: "frame", "depth", "pass 02-stencil-L0", ...
  std::string method;                  // the shadow method rendered, by its scene-file name
  std::string scene;                   // the scene file as given, or "<builtin:room>"
  std::string sceneSha1;               // hex SHA-1 of the scene file's bytes; empty for a built-in scene
  std::vector<std::string> overrides;  // the -D arguments, in order
  int threads = 0;                     // the worker threads the frame ran on (the pixels do not depend on it)
  std::string pipeline;                // "fast": the optimised renderer
  // Further attributes, written after the others in this order: e.g. "shadowref:visibility.L0"
  // naming the light of an EXR's visibility.L0 channel.
  std::vector<std::pair<std::string, std::string>> extra;

  bool empty() const { return software.empty(); }
};

// The attributes to write, in this order (none for empty metadata):
//   Software, ImageDescription (one line for viewers that show only the standard fields),
//   shadowref:content, shadowref:method, shadowref:scene, shadowref:scene-sha1 (when known),
//   shadowref:overrides (when there are some), shadowref:threads, shadowref:pipeline, then `extra`.
// All values are strings. shadowref:overrides is the -D arguments as shell words,
// "-D image.width=64 -D 'ambient=[0.9, 0.9, 0.9]'".
std::vector<std::pair<std::string, std::string>> metadataAttributes(const OutputMetadata& metadata);

// The lower-case hex SHA-1 (40 digits) of the file's bytes, as `sha1sum` prints it. SHA-1 names
// the file's contents; it is not meant to resist a forger. Throws std::runtime_error naming the
// path when the file cannot be read.
std::string sha1OfFile(const std::string& path);

// `word` as one POSIX shell word: unchanged when it holds only characters no shell treats
// specially, otherwise in single quotes (a quote inside as '\'').
std::string shellWord(const std::string& word);

}  // namespace shadowref
