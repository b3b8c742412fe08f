// Which render options a shadow technique has something for: an option that does not apply to the
// method is bad usage (exit 2) with a message that says why, never silently ignored.
#pragma once

#include <string>

#include "cli/render_command.h"
#include "shadow/technique.h"

namespace shadowref::cli {

// "" when every option given applies to `technique`, else the message for the first that does not:
//   --view volumes / volumes-overlay   needs a technique that draws volumes (drawsVolumes)
//   --dump stencil, --dump-region      need stencil counts (countsInStencil)
//   --dump shadowmap                   needs shadow maps (rendersShadowMaps)
//   --stencil-view                     needs stencil counts, and an output that shows them
//                                      (--dump stencil, --dump passes, --dump-region, --pixel-history)
std::string inapplicableRenderOption(const RenderArgs& args, const ShadowTechnique& technique);

}  // namespace shadowref::cli
