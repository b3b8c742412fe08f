// Depth buffers and shadow maps as pictures that show something: auto-ranged over the pixels
// that hold a surface, on the viridis colour map with a colour bar. A depth buffer's window depths
// crowd near 1 under a perspective projection (the room's lie between 0.997 and 0.999, grey 254
// to 255 on a 0..1 grey ramp); shown as the linear eye distance, nearer surfaces are darker and
// equal steps of distance equal steps of colour.
#pragma once

#include <span>

#include <glm/glm.hpp>

#include "gl/render_state.h"
#include "shadow/frame_renderer.h"
#include "views/view.h"

namespace shadowref::views {

// The colour of pixels that hold nothing (the cleared depth 1): a neutral grey that viridis does
// not reach.
inline constexpr Rgb8 kNothingDrawn = {112, 112, 112};

// The eye-space distance along the view axis (−z_eye) of window depth d, through the inverse of
// the projection's depth rows: z_ndc = 2 (d − n) / (f − n) − 1 for the viewport's depth range
// n..f, then z_eye = (P32 − z_ndc P33) / (z_ndc P23 − P22) (glm's [column][row]), which holds for
// a perspective, an infinite (P_inf) and an orthographic projection alike.
double eyeDistance(double windowDepth, const glm::dmat4& projection, const Viewport& viewport);

// The camera's depth buffer (window depths, framebuffer order, row 0 at the bottom) as the eye
// distance of each pixel with a depth below 1, mapped from the least (viridis 0) to the greatest
// (viridis 1) of them; pixels at depth 1 (nothing drawn) kNothingDrawn. A colour bar from lo to
// hi, quantity "eye depth". All pixels at depth 1: a grey picture and no legend.
View depthView(std::span<const float> windowDepth, int width, int height, const glm::dmat4& projection,
               const Viewport& viewport);

// A shadow map's stored depths (framebuffer order), mapped from the least to the greatest depth
// between 0 and 1 exclusive (the texels a caster reached); texels at 0 (a TSM map's casters
// clamped to its near end, the trapezoid drawn into the .plain view) take the low end without
// widening the range (unless every covered texel is 0); texels at 1 kNothingDrawn. Quantity "stored depth": a
// TSM map's depths are warped (light_shadow.h), a perspective map's are not linear; the view
// shows their order, and the colour bar the values the lookups compare with.
View shadowMapView(std::span<const float> depth, int width, int height);

// The colours of the outlines drawn over a shadow map: neither is on viridis nor kNothingDrawn.
inline constexpr Rgb8 kFrustumColour = {255, 255, 255};
inline constexpr Rgb8 kTrapezoidColour = {255, 48, 48};

// Draws over a shadow map's view (shadowMapView, same size as the map) what the map was made
// for: the camera frustum's twelve edges projected by outline.worldToClip, each clipped in clip
// space to the map (-w <= x, y <= w) and to the front of the light (w > 0) before the division,
// in kFrustumColour; then, for TSM's unwarped view, the trapezoid in kTrapezoidColour (the texels
// the map's depth-0 outline holds, shadow/trapezoid_overlay.h). The legend gets the two colours.
void drawShadowMapOutline(View& view, const ShadowMapOutline& outline);

}  // namespace shadowref::views
