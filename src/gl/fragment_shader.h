// The pluggable shading stage: everything that computes a colour (lighting, shadow-map lookups)
// lives outside the rasterizer behind this interface, so that the
// rasterizer stays the same for every shading model.
#pragma once

#include <glm/glm.hpp>

#include "gl/render_state.h"
#include "gl/vertex.h"

namespace shadowref {

struct ShaderDescription;  // gl/shader_description.h

struct FragmentInput {
  int x = 0, y = 0;          // pixel; its centre is (x + 0.5, y + 0.5)
  double depth = 0.0;        // window depth after offset and clamping
  Facing facing = FrontFacing;
  const double* varyings = nullptr;  // perspective-correct, varyingCount() of them
  // The triangle's three vertices as set up (clipped vertices where clipping made them), whose
  // varyings the fragment's are interpolated from: a shader that needs the primitive's plane
  // (a shadow lookup's receiver plane) takes it from them. nullptr where no triangle is known
  // (a vertex shaded alone).
  const ClipVertex* triangle[3]{};
};

// Fragments of one triangle, shaded together: column by column (structure of arrays), so a
// shader can run its arithmetic over all of them in vector registers.
inline constexpr int kMaxBatch = 64;
struct FragmentBatch {
  int count = 0;
  Facing facing = FrontFacing;
  const int* x = nullptr;           // x[k], y[k]: the pixel of fragment k
  const int* y = nullptr;
  const double* depth = nullptr;    // depth[k]
  const double* varyings[kMaxVaryings]{};  // varyings[j][k]: varying j of fragment k
  const ClipVertex* triangle[3]{};         // the triangle's vertices, as FragmentInput::triangle
};

class FragmentShader {
 public:
  virtual ~FragmentShader() = default;
  // How many varyings of the vertices this shader reads; the rasterizer interpolates only those.
  virtual int varyingCount() const = 0;
  virtual glm::dvec4 shade(const FragmentInput& in) const = 0;
  // The colour every fragment gets when it does not depend on the fragment, else nullptr: the
  // rasterizer then skips interpolation and the call per fragment.
  virtual const glm::dvec4* constantColor() const { return nullptr; }
  // shade() for every fragment of the batch; a shader overrides it to work on all at once. It
  // must give the bits shade() gives.
  virtual void shadeBatch(const FragmentBatch& batch, glm::dvec4* out) const;
  // The shader as data (gl/shader_description.h), for a capture of the draws (src/trace); false
  // when it cannot be given as such.
  virtual bool describe(ShaderDescription& out) const { return false; }
};

// Outputs the first four varyings as RGBA: flat or Gouraud colour, and the conformance tests.
class ColorVaryingShader final : public FragmentShader {
 public:
  int varyingCount() const override { return 4; }
  glm::dvec4 shade(const FragmentInput& in) const override {
    return {in.varyings[0], in.varyings[1], in.varyings[2], in.varyings[3]};
  }
  void shadeBatch(const FragmentBatch& batch, glm::dvec4* out) const override;
  bool describe(ShaderDescription& out) const override;
};

// One colour for every fragment.
class ConstantColorShader final : public FragmentShader {
 public:
  explicit ConstantColorShader(const glm::dvec4& color) : color_(color) {}
  int varyingCount() const override { return 0; }
  glm::dvec4 shade(const FragmentInput&) const override { return color_; }
  const glm::dvec4* constantColor() const override { return &color_; }
  bool describe(ShaderDescription& out) const override;

 private:
  glm::dvec4 color_;
};

}  // namespace shadowref
