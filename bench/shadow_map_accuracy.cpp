// bench/shadow_map_accuracy: how many pixels a shadow map gets
// wrong, against the ray-traced light visibility of the oracle (src/oracle), for
// standard and trapezoidal maps at 128 … 4096 texels and each anti-self-shadowing choice.
//
// Per scene the oracle casts one primary ray per pixel and a shadow ray from its hit to the light.
// Each configuration builds the light's map(s) exactly as a frame does (light_shadow.h) and looks
// them up at the oracle's hit points; a pixel is wrong when the map shadows it (factor < 1) and
// the light sees it (false shadow), or the map lights it and the light does not (missed shadow).
// Spot lights count only points inside the cone (outside it nothing is lit to be shadowed).
//
//   shadow_map_accuracy [--quick] [--scene NAME] [--sizes N,N,...] [-D KEY=VALUE]... [--images DIR] [--csv FILE]
//
// --scene and --sizes pick one scene and the map sizes; -D changes every scene as the command
// line's -D does (on top of each anti-self-shadowing choice).
//
// --images writes, per scene, the oracle's shadow and each configuration's error picture (grey:
// right, red: false shadow, blue: missed shadow) and the frame itself, for docs/shadow-maps.md.
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "image/image_writer.h"
#include "scene/scene_loader.h"
#include "shadow/frame_renderer.h"
#include "shadow/light_shadow.h"
#include "shadow/scene_view.h"
#include "shadow/shadow_map_accuracy.h"
#include "oracle/oracle.h"
#include "oracle/visibility_comparison.h"

namespace shadowref::bench {

namespace {

struct SceneCase {
  std::string name;   // for the table
  std::string file;   // scenes/<file>.yaml
  std::vector<std::string> overrides;
  bool tsm = true;    // point lights have cube maps only
};

struct AntiAcne {
  std::string name;
  std::vector<std::string> overrides;
};

// The anti-self-shadowing choices of [Hempe 2004, §3.2] (and none, for reference). The constant
// bias is in window depth units of the map; 1e-4 of the outdoor scene's light depth range (~560 m)
// is about 6 cm, of the room's (~9 m) about 1 mm.
std::vector<AntiAcne> antiAcneChoices() {
  return {{"offset", {}},  // the default: factor 1.1, units 4
          {"bias", {"shadow.offset_factor=0", "shadow.offset_units=0", "shadow.bias=0.0001"}},
          {"backfaces", {"shadow.offset_factor=0", "shadow.offset_units=0", "shadow.back_faces_only=true"}},
          {"none", {"shadow.offset_factor=0", "shadow.offset_units=0"}}};
}

std::vector<SceneCase> sceneCases() {
  return {{"outdoor", "outdoor", {}, true},
          {"room", "room", {}, false},
          // The room's ceiling light as a spot straight down: TSM needs a directional or spot light.
          {"room-spot", "room", {"lights.0.type=spot", "lights.0.direction=[0, -1, 0]", "lights.0.spot_cutoff=70"}, true},
          // 16 houses under a sun on a 224 m slab: the map fitted to the casters that shadow what
          // the camera sees (light_view.h) instead of the whole slab.
          {"city16-sun", "city16_sun", {}, true},
          // spot.yaml's light from the side, 30° above the floor at its centre: a grazing, sloped
          // receiver (the oblique spot of the PCF rows in docs/shadow-maps.md).
          {"spot-side", "spot", {"lights.0.position=[5, 3, 2]", "lights.0.direction=[-5, -3, -2]", "lights.0.spot_cutoff=40"}, true}};
}

Scene load(const SceneCase& c, const std::vector<std::string>& extra) {
  LoadOptions options;
  options.overrides = c.overrides;
  options.overrides.insert(options.overrides.end(), extra.begin(), extra.end());
  return loadScene(std::string(SHADOWREF_SOURCE_DIR) + "/scenes/" + c.file + ".yaml", options);
}

void writeErrorImage(const LightShadow& shadow, const oracle::OracleImage& o, const std::vector<uint8_t>& mask,
                     const std::vector<glm::dvec4>& planes, const std::string& path) {
  Image8 img;
  img.width = o.width;
  img.height = o.height;
  img.channels = 3;
  img.pixels = oracle::compareVisibility(
                   o, mask, [&](size_t i) { return !(shadow.factor(o.hitPoint[i], planes[i]) < 1.0); },
                   /*paleNearEdges=*/false)
                   .errorMap;
  writePng8(img, path);
}

void writeOracleImage(const oracle::OracleImage& o, const std::vector<uint8_t>& mask, const std::string& path) {
  Image8 img;
  img.width = o.width;
  img.height = o.height;
  img.channels = 1;
  img.pixels.assign(size_t(o.width) * size_t(o.height), 0);
  for (int y = 0; y < o.height; ++y)
    for (int x = 0; x < o.width; ++x) {
      const size_t i = o.index(x, y);
      if (mask[i]) img.pixels[size_t(o.height - 1 - y) * size_t(o.width) + size_t(x)] = o.lit[i] ? 200 : 90;
    }
  writePng8(img, path);
}

}  // namespace

int run(int argc, char** argv) {
  bool quick = false;
  std::string images, csvPath, only;
  std::vector<int> chosenSizes;
  std::vector<std::string> extraOverrides;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--quick")) quick = true;
    else if (!std::strcmp(argv[i], "--images") && i + 1 < argc) images = argv[++i];
    else if (!std::strcmp(argv[i], "--csv") && i + 1 < argc) csvPath = argv[++i];
    else if (!std::strcmp(argv[i], "--scene") && i + 1 < argc) only = argv[++i];
    else if (!std::strcmp(argv[i], "-D") && i + 1 < argc) extraOverrides.push_back(argv[++i]);
    else if (!std::strcmp(argv[i], "--sizes") && i + 1 < argc) {
      for (std::string list = argv[++i]; !list.empty();) {
        const size_t comma = list.find(',');
        const int size = std::atoi(list.substr(0, comma).c_str());
        if (size < 8 || size > 8192) {
          std::cerr << "shadow_map_accuracy: --sizes takes map sizes from 8 to 8192\n";
          return 2;
        }
        chosenSizes.push_back(size);
        list = comma == std::string::npos ? "" : list.substr(comma + 1);
      }
    } else {
      std::cerr << "usage: shadow_map_accuracy [--quick] [--scene NAME] [--sizes N,N,...] [-D KEY=VALUE]... [--images DIR] [--csv FILE]\n";
      return 2;
    }
  }
  const std::vector<int> sizes = !chosenSizes.empty() ? chosenSizes
                                 : quick             ? std::vector<int>{256, 1024}
                                                     : std::vector<int>{128, 256, 512, 1024, 2048, 4096};
  std::ofstream csv;
  if (!csvPath.empty()) {
    csv.open(csvPath);
    csv << "scene,method,anti_acne,map_size,points,false_shadow,missed_shadow,wrong_percent\n";
  }
  std::printf("%-10s %-9s %-9s %6s %9s %8s %8s %8s\n", "scene", "method", "anti-acne", "size", "pixels", "false", "missed",
              "wrong %");
  for (const SceneCase& sc : sceneCases()) {
    if (!only.empty() && sc.name != only) continue;
    const Scene base = load(sc, extraOverrides);
    const Light& light = base.lights.at(0);
    oracle::OracleOptions oo;
    const oracle::OracleImage o = oracle::castOracle(base, light, oo);
    const std::vector<uint8_t> mask = oracle::comparedPixels(o, light);
    const std::vector<glm::dvec4> planes = oracle::hitPlanes(o, base.instances());
    if (!images.empty()) writeOracleImage(o, mask, images + "/" + sc.name + "-oracle.png");
    for (const char* method : {"shadowmap", "tsm"}) {
      const bool trapezoidal = std::string(method) == "tsm";
      if (trapezoidal && !sc.tsm) continue;
      for (const AntiAcne& a : antiAcneChoices()) {
        if (quick && a.name != "offset") continue;
        for (int size : sizes) {
          std::vector<std::string> extra = a.overrides;
          extra.insert(extra.end(), extraOverrides.begin(), extraOverrides.end());
          extra.push_back("shadow.map_size=" + std::to_string(size));
          const Scene scene = load(sc, extra);
          const std::vector<Instance> instances = scene.instances();
          RasterStats stats;
          Framebuffer frame(1, 1);  // the maps' pipelines are made like this one: on every core
          const auto shadow = buildLightShadow(scene, instances, makeCameraView(scene), scene.lights.at(0), trapezoidal,
                                               *makePipeline(PipelineKind::Fast, frame, 0), stats);
          const ShadowMapErrors e = countShadowErrors(*shadow, o.hitPoint, o.lit, mask, planes);
          std::printf("%-10s %-9s %-9s %6d %9zu %8zu %8zu %8.3f\n", sc.name.c_str(), method, a.name.c_str(), size, e.points,
                      e.falseShadow, e.missedShadow, 100.0 * e.wrongFraction());
          std::fflush(stdout);
          if (csv) csv << sc.name << ',' << method << ',' << a.name << ',' << size << ',' << e.points << ',' << e.falseShadow
                       << ',' << e.missedShadow << ',' << 100.0 * e.wrongFraction() << '\n';
          if (!images.empty()) {
            const std::string stem = images + "/" + sc.name + "-" + method + "-" + a.name + "-" + std::to_string(size);
            writeErrorImage(*shadow, o, mask, planes, stem + "-errors.png");
            if (a.name == "offset") {
              FrameOptions fo;
              fo.method = trapezoidal ? "tsm" : "shadowmap";
              fo.threads = 0;
              writePng(renderFrame(scene, fo).framebuffer, stem + ".png");
            }
          }
        }
      }
    }
  }
  return 0;
}

}  // namespace shadowref::bench

int main(int argc, char** argv) {
  try {
    return shadowref::bench::run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "shadow_map_accuracy: " << e.what() << '\n';
    return 1;
  }
}
