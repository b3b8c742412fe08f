// describe() of the shaders of src/gl: each gives the parameters it was made from.
#include "gl/shader_description.h"

#include "gl/fragment_shader.h"
#include "gl/lighting.h"

namespace shadowref {

bool ColorVaryingShader::describe(ShaderDescription& out) const {
  out = {};
  out.kind = ShaderKind::ColorVarying;
  return true;
}

bool ConstantColorShader::describe(ShaderDescription& out) const {
  out = {};
  out.kind = ShaderKind::Constant;
  out.color = color_;
  return true;
}

bool PerPixelLightingShader::describe(ShaderDescription& out) const {
  out = {};
  out.kind = ShaderKind::PerPixelLighting;
  out.setup = setup_;
  return true;
}

bool GouraudShader::describe(ShaderDescription& out) const {
  out = {};
  out.kind = ShaderKind::Gouraud;
  return true;
}

}  // namespace shadowref
