// Failure reports with pictures, as dEQP's and piglit's give: for each failing case a folder with
// the reference, the result and their difference as PNG, one HTML page that shows them beside the
// comparison's numbers, and an index page over every case in the report folder. Written by the
// golden tests when a golden does not match (and so by scripts/update-goldens.sh before it writes).
#pragma once

#include <string>

#include "image/channel_image.h"
#include "image/image_compare.h"

namespace shadowref {

struct ReportCase {
  std::string name;                 // a file-name-safe case name, e.g. "room-zfail"
  std::string referenceLabel = "reference";
  std::string resultLabel = "result";
  std::string note;                 // a paragraph of plain text above the pictures (may be empty)
  const ChannelImage* reference = nullptr;
  const ChannelImage* result = nullptr;
  const CompareResult* comparison = nullptr;  // may be null: then compared with exact tolerances
};

// Writes <folder>/<name>/reference.png, result.png, difference.png (the colour, or the first
// channel, of each image and the heat map of every channel's largest difference), a row of
// pictures per differing channel (<channel>-reference.png, ...-result.png, ...-difference.png),
// <folder>/<name>/index.html, and rewrites <folder>/index.html to link every case page under
// <folder>. Returns the case page's path. A case of another size than its reference gets the two
// pictures and no difference. Throws std::runtime_error when a file cannot be written.
std::string writeFailureReport(const std::string& folder, const ReportCase& c);

// The 8-bit picture of an image for looking at: R, G, B (clamped to [0, 1]) when it has them,
// otherwise its first channel; `channel` names one channel instead. A float channel is drawn in
// grey from its smallest to its largest finite value, an integer channel (a stencil) in the
// stencil view's false colours (count 0 black, 1 red, 2 green, ...).
Image8 viewOf(const ChannelImage& image, const std::string& channel = "");

}  // namespace shadowref
