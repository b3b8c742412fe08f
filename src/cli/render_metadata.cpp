#include "cli/render_metadata.h"

#include "cli/version_info.h"
#include "gl/pipeline.h"

namespace shadowref::cli {

OutputMetadata renderMetadata(const RenderArgs& args, const Scene& scene, const FrameOptions& options) {
  OutputMetadata m;
  m.software = softwareName();
  m.method = options.method.empty() ? scene.shadow.method : options.method;
  // The file as named on the command line: the same command gives the same metadata anywhere.
  m.scene = args.scene.scene.empty() ? scene.sourceFile : args.scene.scene;
  if (!args.scene.scene.empty()) m.sceneSha1 = sha1OfFile(args.scene.scene);
  m.overrides = args.scene.overrides;
  m.threads = pipelineThreads(options.pipeline, options.threads);
  m.pipeline = name(options.pipeline);
  return m;
}

}  // namespace shadowref::cli
