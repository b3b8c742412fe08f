#include "cli/render_option_checks.h"

#include <algorithm>

#include "shadow/technique_registry.h"

namespace shadowref::cli {

namespace {

bool wants(const std::vector<std::string>& dumps, const char* what) {
  return std::find(dumps.begin(), dumps.end(), what) != dumps.end();
}

// "zpass, zfail, auto": the built-in techniques that have the output.
std::string namesWith(bool ShadowTechnique::*has) {
  std::string names;
  for (const ShadowTechnique* t : techniques())
    if (t->*has) names += (names.empty() ? "" : ", ") + std::string(t->name);
  return names;
}

std::string notFor(const std::string& option, const ShadowTechnique& technique, const std::string& lacks,
                   bool ShadowTechnique::*has) {
  return option + ": the method '" + std::string(technique.name) + "' " + lacks + "; it applies to " + namesWith(has) +
         " (--method NAME)";
}

}  // namespace

std::string inapplicableRenderOption(const RenderArgs& args, const ShadowTechnique& technique) {
  if (!args.view.empty() && !technique.drawsVolumes)
    return notFor("--view " + args.view, technique, "draws no shadow volumes", &ShadowTechnique::drawsVolumes);
  if (wants(args.dumps, "stencil") && !technique.countsInStencil)
    return notFor("--dump stencil", technique, "counts nothing in the stencil buffer", &ShadowTechnique::countsInStencil);
  if (!args.dumpRegion.empty() && !technique.countsInStencil)
    return notFor("--dump-region", technique, "counts nothing in the stencil buffer", &ShadowTechnique::countsInStencil);
  if (wants(args.dumps, "shadowmap") && !technique.rendersShadowMaps)
    return notFor("--dump shadowmap", technique, "renders no shadow map", &ShadowTechnique::rendersShadowMaps);
  if (!args.stencilView.empty()) {
    if (!technique.countsInStencil)
      return notFor("--stencil-view", technique, "counts nothing in the stencil buffer", &ShadowTechnique::countsInStencil);
    if (!wants(args.dumps, "stencil") && !wants(args.dumps, "passes") && args.dumpRegion.empty() &&
        args.pixelHistory.empty())
      return "--stencil-view: nothing shows stencil counts; it applies to --dump stencil, --dump passes, "
             "--dump-region and --pixel-history";
  }
  return "";
}

}  // namespace shadowref::cli
