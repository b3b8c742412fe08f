#include "conformance/edge_mask.h"

#include "trace/edge_mask.h"

namespace shadowref::conformance {

// The product's classification (src/trace/edge_mask.h, used by `shadowref replay`), over the
// scenario's draws.
std::vector<bool> edgeMask(const Scenario& scenario, double distance) {
  trace::EdgeMask mask(scenario.width, scenario.height);
  for (const Step& step : scenario.steps) {
    const auto* d = std::get_if<DrawStep>(&step);
    if (!d) continue;
    for (size_t first = 0; first + 2 < d->vertices.size(); first += 3)
      mask.addTriangle(d->vertices[first].clip, d->vertices[first + 1].clip, d->vertices[first + 2].clip,
                       d->state.viewport, d->state.depthClamp, distance);
  }
  return mask.mask();
}

}  // namespace shadowref::conformance
