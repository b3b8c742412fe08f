// The provenance of a render's files (image/output_metadata.h), from its arguments and this build.
#pragma once

#include "cli/render_command.h"
#include "image/output_metadata.h"
#include "scene/scene.h"
#include "shadow/frame_renderer.h"

namespace shadowref::cli {

// Every field but `content`, which names each file's picture. Hashes the scene file (throws
// std::runtime_error when it cannot be read); threads 0 is recorded as the count it stands for.
OutputMetadata renderMetadata(const RenderArgs& args, const Scene& scene, const FrameOptions& options);

}  // namespace shadowref::cli
