// A picture as PNG bytes in memory, for the explorer's frames: a local connection and the browser
// pass a few hundred kilobytes of PNG with far less work than 2 MB of raw pixels, and PNG is
// lossless, so the page shows exactly the rendered bytes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace shadowref::explore {

// RGBA pixels, top row first, as an RGB PNG (alpha dropped), zlib level 1 and no filter: rendered
// frames repeat whole pixels (flat walls, sky, background), which deflate finds unfiltered, while a
// filter turns them into differences that repeat less; unfiltered is both the smaller and the
// faster to encode and to decode. Throws std::runtime_error.
std::string encodePngRgb(const std::vector<uint8_t>& rgba, int width, int height);

}  // namespace shadowref::explore
