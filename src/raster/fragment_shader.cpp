#include "raster/fragment_shader.h"

namespace shadowref {

void FragmentShader::shadeBatch(const FragmentBatch& batch, glm::dvec4* out) const {
  const int count = varyingCount();
  for (int k = 0; k < batch.count; ++k) {
    double varyings[kMaxVaryings];
    for (int j = 0; j < count; ++j) varyings[j] = batch.varyings[j][k];
    FragmentInput in;
    in.x = batch.x[k];
    in.y = batch.y;
    in.depth = batch.depth[k];
    in.facing = batch.facing;
    in.varyings = varyings;
    out[k] = shade(in);
  }
}

}  // namespace shadowref
