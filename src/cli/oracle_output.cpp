#include "cli/oracle_output.h"

#include <cmath>
#include <cstdio>
#include <ostream>
#include <stdexcept>

#include "gl/pipeline.h"
#include "image/image_writer.h"
#include "oracle/oracle.h"
#include "oracle/visibility_comparison.h"
#include "shadow/light_shadow.h"
#include "shadow/scene_view.h"
#include "shadow/shadow_map_accuracy.h"
#include "shadow/technique.h"

namespace shadowref::cli {

std::vector<OracleLightFigures> writeOracleOutputs(const Scene& scene, const std::string& method,
                                                   const FrameResult& frame,
                                                   const std::function<std::string(const std::string&)>& sibling,
                                                   std::vector<std::string>& written, std::ostream& out) {
  if (frame.visibility.size() != scene.lights.size())
    throw std::runtime_error("--oracle: the frame kept no visibility for every light");
  const bool mapMethod = method == "shadowmap" || method == "tsm";
  // The volume methods draw with P_inf ([Kuhn 2016, §3.3]); the oracle's camera must see the same
  // surfaces, beyond the far plane included.
  oracle::OracleOptions options;
  options.forceInfiniteProjection = !mapMethod && method != "none";
  const int w = scene.width, h = scene.height;
  std::vector<OracleLightFigures> figures;
  for (size_t l = 0; l < scene.lights.size(); ++l) {
    const Light& light = scene.lights[l];
    const oracle::OracleImage o = oracle::castOracle(scene, light, options);
    const std::vector<uint8_t> mask = oracle::comparedPixels(o, light);
    const std::vector<float>& rendered = frame.visibility[l];
    // A PCF or soft fraction below 1 counts as shadow, as the shadow test's factor < 1 does.
    oracle::VisibilityComparison c = oracle::compareVisibility(
        o, mask, [&](size_t i) { return rendered[i] >= 1.0f; }, /*paleNearEdges=*/true);
    OracleLightFigures f;
    static_cast<oracle::VisibilityCounts&>(f) = c.counts;
    std::vector<float> traced(size_t(w) * size_t(h), 1.0f);
    for (size_t i = 0; i < traced.size(); ++i)
      if (o.hitMask[i]) traced[i] = o.lit[i] ? 1.0f : 0.0f;
    Image8 errors;
    errors.width = w;
    errors.height = h;
    errors.channels = 3;
    errors.pixels = std::move(c.errorMap);
    if (mapMethod) {
      // The accuracy table's measure: the map built as a frame builds it, tested at the oracle's
      // surface points instead of the rasterized ones.
      RasterStats stats;
      Framebuffer holder(1, 1);
      const std::vector<Instance> instances = scene.instances();
      const auto shadow = buildLightShadow(scene, instances, makeCameraView(scene), light, method == "tsm",
                                           *makePipeline(PipelineKind::Fast, holder, 0), stats);
      const ShadowMapErrors e = countShadowErrors(*shadow, o.hitPoint, o.lit, mask, oracle::hitPlanes(o, instances));
      f.mapPoints = e.points;
      f.mapFalseShadow = e.falseShadow;
      f.mapMissedShadow = e.missedShadow;
    }
    const std::string name = "L" + std::to_string(l);
    const std::string tracedPath = sibling("oracle-" + name), errorPath = sibling("oracle-errors-" + name);
    writeGreyPng(traced, w, h, tracedPath, 0.0f, 1.0f);
    writePng8(errors, errorPath);
    written.push_back(tracedPath);
    written.push_back(errorPath);
    char line[512];
    std::snprintf(line, sizeof line,
                  "oracle %s '%s': %zu pixels compared, %.2f %% agree; %zu differ: %zu near an edge, %zu elsewhere "
                  "(false shadow %zu, missed shadow %zu)\n",
                  name.c_str(), light.name.c_str(), f.compared, f.agreePercent(), f.compared - f.agree, f.nearEdge,
                  f.elsewhere, f.falseShadow, f.missedShadow);
    out << line << std::flush;  // before the "wrote" lines on stderr
    if (mapMethod) {
      std::snprintf(line, sizeof line,
                    "  map test at the oracle's surface points: %zu points, false shadow %zu, missed shadow %zu, "
                    "%.2f %% wrong\n",
                    f.mapPoints, f.mapFalseShadow, f.mapMissedShadow, f.mapWrongPercent());
      out << line << std::flush;
    }
    figures.push_back(f);
  }
  return figures;
}

}  // namespace shadowref::cli
