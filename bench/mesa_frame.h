// The Mesa side of bench/vs-mesa (issue 7): the same frame as shadowref's renderFrame, issued as
// OpenGL 2.1 calls to OSMesa (softpipe or llvmpipe, as GALLIUM_DRIVER chose).
//
// Same geometry and the same passes, not the same shading:
//  - stencil shadow volumes (000 §3.1; volume_renderer.cpp): ambient pass (depth LESS), per light
//    a stencil clear, the z-fail / z-pass volumes of every caster in range built on the CPU each
//    frame with buildShadowVolume (the very function shadowref uses) and drawn with w = 0 points
//    under P_inf in the RenderStates of volumePassStates, then the lit pass with stencil EQUAL 0,
//    depth LEQUAL and ONE/ONE blending;
//  - shadow maps (002 §3.1): the depth map from the light into a map_size² depth texture (a
//    framebuffer object, polygon offset as the scene says), then one camera pass with
//    ARB_shadow's depth compare, EYE_LINEAR texgen and the texture matrix T = bias · P · V.
// Lighting is GL's fixed function, i.e. PER VERTEX (Gouraud), where shadowref's materials light
// per pixel: Mesa does less work per fragment than shadowref here, which flatters Mesa. The
// shadow-map compare-fail value is 0 (GL 2.1 without ARB_shadow_ambient), shadowref's 0.4.
#pragma once

#include <memory>

#include "raster/framebuffer.h"
#include "scene/scene.h"

namespace shadowref::bench {

class MesaFrameRenderer {
 public:
  // Creates (through the conformance harness) and makes current an OSMesa context of the scene's
  // size. Throws std::runtime_error for a method or light type the GL side does not draw.
  explicit MesaFrameRenderer(const Scene& scene, ShadowMethod method);
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
