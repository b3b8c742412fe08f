// Reading a file named by input (a mesh file, a glTF buffer, any side file): only a regular file
// of bounded size is read, and its size is known before a byte is read. A device (/dev/zero), a
// FIFO or a folder would otherwise be read until memory runs out, block forever, or be taken for
// a file of 2^63 bytes.
#pragma once

#include <cstdint>
#include <string>

namespace shadowref {

// Mesh files and the buffers they refer to: 256 MiB is some ten million triangles with normals,
// more than the scene's triangle budget can use.
inline constexpr std::uint64_t kMaxInputFileBytes = std::uint64_t{256} << 20;

// A scene file is hand-written text: 64 MiB is far beyond any real one, and bounds what the YAML
// parser is given before it builds a node tree several times the text's size.
inline constexpr std::uint64_t kMaxSceneFileBytes = std::uint64_t{64} << 20;

// The size of `path` in bytes after checking that it exists, is a regular file and has at most
// `maxBytes` bytes. Throws SceneError at `path` (no line) naming `what` ("mesh file", "buffer").
std::uint64_t checkInputFile(const std::string& path, const std::string& what,
                             std::uint64_t maxBytes = kMaxInputFileBytes);

// The whole contents of `path`, with the checks of checkInputFile made on the opened descriptor
// (so a file swapped for a FIFO between check and open cannot block) before anything is read.
std::string readInputFile(const std::string& path, const std::string& what,
                          std::uint64_t maxBytes = kMaxInputFileBytes);

}  // namespace shadowref
