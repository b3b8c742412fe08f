#include "gl/fragment_shader.h"

namespace shadowref {

void FragmentShader::shadeBatch(const FragmentBatch& batch, glm::dvec4* out) const {
  const int count = varyingCount();
  for (int k = 0; k < batch.count; ++k) {
    double varyings[kMaxVaryings];
    for (int j = 0; j < count; ++j) varyings[j] = batch.varyings[j][k];
    FragmentInput in;
    in.x = batch.x[k];
    in.y = batch.y[k];
    in.depth = batch.depth[k];
    in.facing = batch.facing;
    in.varyings = varyings;
    for (int i = 0; i < 3; ++i) in.triangle[i] = batch.triangle[i];
    out[k] = shade(in);
  }
}

// shade() for every fragment: the four interpolated columns, copied.
void ColorVaryingShader::shadeBatch(const FragmentBatch& batch, glm::dvec4* out) const {
  const double *r = batch.varyings[0], *g = batch.varyings[1], *b = batch.varyings[2], *a = batch.varyings[3];
  for (int k = 0; k < batch.count; ++k) out[k] = {r[k], g[k], b[k], a[k]};
}

}  // namespace shadowref
