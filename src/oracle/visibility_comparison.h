// A rendered shadow judged by the oracle's light visibility, pixel by pixel: which pixels can be
// judged, how many agree, and the error map that shows where they do not. `shadowref render
// --oracle` and bench/shadow_map_accuracy both use it, so their counts and colours mean the same.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "oracle/oracle.h"
#include "scene/scene.h"

namespace shadowref::oracle {

// The pixels a rendered shadow can be judged at: every hit, and for a spot light only those
// inside its cone (outside it nothing is lit to be shadowed).
std::vector<uint8_t> comparedPixels(const OracleImage& o, const Light& light);

struct VisibilityCounts {
  size_t compared = 0;      // pixels in the mask
  size_t agree = 0;         // the render and the oracle say the same
  size_t falseShadow = 0;   // rendered in shadow, the light sees the point
  size_t missedShadow = 0;  // rendered lit, the light does not see the point
  size_t nearEdge = 0;      // differing pixels the oracle marks as near an edge (OracleImage::nearEdge)
  size_t elsewhere = 0;     // the other differing pixels

  double agreePercent() const { return compared ? 100.0 * double(agree) / double(compared) : 100.0; }
};

struct VisibilityComparison {
  VisibilityCounts counts;
  // RGB, 8 bits, top row first (as a PNG stores it), o.width × o.height: black not compared, grey
  // where both agree (200 lit, 90 in shadow), red (255, 0, 0) a false shadow, blue (0, 64, 255) a
  // missed shadow; with paleNearEdges, (255, 160, 160) and (150, 180, 255) near an edge.
  std::vector<uint8_t> errorMap;
};

// Compares renderedLit(i) — whether the render lights pixel i = o.index(x, y), called only where
// mask[i] is set — with o.lit[i]. mask has one entry per pixel (comparedPixels).
VisibilityComparison compareVisibility(const OracleImage& o, const std::vector<uint8_t>& mask,
                                       const std::function<bool(size_t)>& renderedLit, bool paleNearEdges);

}  // namespace shadowref::oracle
