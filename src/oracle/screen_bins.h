// Screen tiles listing the volume triangles a pixel ray may cross — the oracle's acceleration
// structure for shadow-volume polygons.
//
// Why tiles and not a world-space BVH: volume polygons reach infinity (w = 0 vertices, back caps
// in the plane at infinity), so their world bounds are unbounded. But every counting ray starts at
// the eye and runs beyond the near plane, so it can only meet the part of a triangle that lies in
// front of the near plane and inside the (guard-banded) view frustum; that part projects to a
// bounded window region. A triangle is listed in every tile its clipped projection's bounding box
// (grown by one pixel) touches — conservative; the exact projective test (projective_crossing.h)
// decides the crossing.
#pragma once

#include <cstdint>
#include <vector>

#include "oracle/camera_model.h"
#include "oracle/world_volumes.h"

namespace shadowref::oracle {

class ScreenBins {
 public:
  static constexpr int kTile = 8;
  ScreenBins(const CameraModel& camera, const WorldVolumes& volumes);
  const std::vector<uint32_t>& at(int x, int y) const { return tiles_[(y / kTile) * columns_ + x / kTile]; }

 private:
  int columns_ = 0, rows_ = 0;
  std::vector<std::vector<uint32_t>> tiles_;
};

}  // namespace shadowref::oracle
