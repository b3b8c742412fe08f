#include "cli/oracle_output.h"

#include <cmath>
#include <cstdio>
#include <ostream>
#include <stdexcept>

#include "gl/pipeline.h"
#include "image/image_writer.h"
#include "oracle/oracle.h"
#include "shadow/light_shadow.h"
#include "shadow/scene_view.h"
#include "shadow/shadow_map_accuracy.h"
#include "shadow/technique.h"

namespace shadowref::cli {

namespace {

// The pixels to compare: every hit, and for a spot light only those inside its cone (outside it
// nothing is lit to be shadowed) — as bench/shadow_map_accuracy counts them.
std::vector<uint8_t> comparedPixels(const oracle::OracleImage& o, const Light& light) {
  std::vector<uint8_t> mask = o.hitMask;
  if (light.type != LightType::Spot) return mask;
  const double cosCutoff = std::cos(light.spotCutoffDegrees * M_PI / 180.0);
  for (size_t i = 0; i < mask.size(); ++i)
    if (mask[i] && glm::dot(glm::normalize(o.hitPoint[i] - light.position), glm::normalize(light.direction)) < cosCutoff)
      mask[i] = 0;
  return mask;
}

}  // namespace

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
    const std::vector<uint8_t> mask = comparedPixels(o, light);
    const std::vector<float>& rendered = frame.visibility[l];
    OracleLightFigures f;
    std::vector<float> traced(size_t(w) * size_t(h), 1.0f);
    Image8 errors;
    errors.width = w;
    errors.height = h;
    errors.channels = 3;
    errors.pixels.assign(size_t(w) * size_t(h) * 3, 0);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const size_t i = o.index(x, y);
        if (o.hitMask[i]) traced[i] = o.lit[i] ? 1.0f : 0.0f;
        if (!mask[i]) continue;
        ++f.compared;
        const bool renderedLit = rendered[i] >= 1.0f;
        const bool tracedLit = o.lit[i] != 0;
        uint8_t* px = &errors.pixels[(size_t(h - 1 - y) * size_t(w) + size_t(x)) * 3];
        if (renderedLit == tracedLit) {
          ++f.agree;
          px[0] = px[1] = px[2] = tracedLit ? 200 : 90;
          continue;
        }
        const bool edge = o.nearEdge[i] != 0;
        ++(edge ? f.nearEdge : f.elsewhere);
        if (tracedLit) {
          ++f.falseShadow;
          px[0] = 255, px[1] = edge ? 160 : 0, px[2] = edge ? 160 : 0;
        } else {
          ++f.missedShadow;
          px[0] = edge ? 150 : 0, px[1] = edge ? 180 : 64, px[2] = 255;
        }
      }
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
