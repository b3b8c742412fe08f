// `shadowref render ... --oracle`: the ray-cast oracle (src/oracle) on the user's own scene. Per
// scene light it writes the ray-traced light visibility and an error map of the rendered
// visibility (--dump visibility) against it, and prints how far they agree — the judgement
// docs/shadow-maps.md makes on the documents' scenes. For the shadow-map methods it also prints
// the measure of that document's accuracy table: the map's test at the oracle's surface points.
#pragma once

#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include "oracle/visibility_comparison.h"
#include "scene/scene.h"
#include "shadow/frame_renderer.h"

namespace shadowref::cli {

// The rendered visibility against the oracle's (oracle::compareVisibility): compared counts the
// pixels whose primary ray hits, inside a spot light's cone; a visibility below 1 is shadow.
struct OracleLightFigures : oracle::VisibilityCounts {
  // The shadow-map methods: the map's own test at the oracle's hit points (countShadowErrors),
  // bench/shadow_map_accuracy's figure; points == 0 for the other methods.
  size_t mapPoints = 0, mapFalseShadow = 0, mapMissedShadow = 0;

  double mapWrongPercent() const {
    return mapPoints ? 100.0 * double(mapFalseShadow + mapMissedShadow) / double(mapPoints) : 0.0;
  }
};

// Runs the oracle for every light of `scene`, compares with frame.visibility (which must hold one
// vector per light: FrameOptions::keepVisibility), writes per light `sibling("oracle-L<i>")` (grey:
// the ray-traced visibility, 1 white, 0 black, the background white) and
// `sibling("oracle-errors-L<i>")` (error map: not compared black, agreeing pixels grey — light
// where lit, dark where shadowed —, false shadow red, missed shadow blue, each paler near an edge),
// appending each path to `written`, and prints one summary per light to `out`. `method` is the
// technique the frame used. Throws std::runtime_error when a file cannot be written.
std::vector<OracleLightFigures> writeOracleOutputs(const Scene& scene, const std::string& method,
                                                   const FrameResult& frame,
                                                   const std::function<std::string(const std::string&)>& sibling,
                                                   std::vector<std::string>& written, std::ostream& out);

}  // namespace shadowref::cli
