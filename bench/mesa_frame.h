// The Mesa side of bench/vs-mesa: the same frame as shadowref's renderFrame, issued as
// OpenGL 2.1 calls to OSMesa (softpipe or llvmpipe, as GALLIUM_DRIVER chose).
//
// Same geometry and the same passes, not the same shading:
//  - stencil shadow volumes ([Kuhn 2016, §3.1]; volume_renderer.cpp): ambient pass (depth LESS),
//    per light a stencil clear, the z-fail / z-pass volumes of every caster in range built on the
//    CPU each frame with buildShadowVolume (the very function shadowref uses) and drawn with w = 0
//    points under P_inf in the RenderStates of volumePassStates, then the lit pass with stencil
//    EQUAL 0, depth LEQUAL and ONE/ONE blending;
//  - shadow maps ([Hempe 2004, §3.1]): the depth map from the light into a map_size² depth texture
//    (a framebuffer object, polygon offset as the scene says), then one camera pass with
//    ARB_shadow's depth compare, EYE_LINEAR texgen and the texture matrix T = bias · P · V.
// Lighting, the MesaLighting choice:
//  - FixedFunction: GL's fixed-function lighting, i.e. PER VERTEX (Gouraud), where shadowref's
//    materials light per pixel: Mesa does less work per fragment than shadowref, which flatters
//    Mesa. The shadow-map compare-fail value is 0 (GL 2.1 without ARB_shadow_ambient), shadowref's
//    0.4.
//  - PerPixel: a GLSL 1.20 program with shadowref's per-pixel Phong model (gl/lighting.h:
//    normal renormalised per fragment, flipped on back faces, Phong or Blinn specular with pow), in
//    float, with the light and material terms worked out by shadowref's own lightTerms; in the
//    shadow-map camera pass it also does the depth compare (shadow2DProj on T · world position) and
//    modulates by the scene's compare-fail value, as ShadowMappedShader does. Like for like with
//    shadowref, up to float against double and rasterization ties (vs_mesa --agreement measures it).
//    A Gouraud material in a volume frame stays fixed function (what shadowref's Gouraud does).
//    One program per light count (0 to 8), all compiled in the constructor, as an application
//    would specialise them: a loop to a uniform count made llvmpipe twice as slow.
#pragma once

#include <memory>

#include "gl/framebuffer.h"
#include "scene/scene.h"

namespace shadowref::bench {

enum class MesaLighting { FixedFunction, PerPixel };

const char* lightingName(MesaLighting lighting);

class MesaFrameRenderer {
 public:
  // Creates (through the conformance harness) and makes current an OSMesa context of the scene's
  // size. Throws std::runtime_error for a method or light type the GL side does not draw, and for
  // a shader that does not compile or link (with the info log).
  explicit MesaFrameRenderer(const Scene& scene, std::string_view method,
                             MesaLighting lighting = MesaLighting::FixedFunction);
  ~MesaFrameRenderer();
  MesaFrameRenderer(const MesaFrameRenderer&) = delete;
  MesaFrameRenderer& operator=(const MesaFrameRenderer&) = delete;

  // One whole frame, finished (glFinish): the time to measure.
  void render();

  // The colour buffer as it stands, in a Framebuffer (bytes / 255), for looking at the frame.
  Framebuffer readColor() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace shadowref::bench
