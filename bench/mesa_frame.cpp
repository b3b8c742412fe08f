#include "mesa_frame.h"

#include <GL/osmesa.h>

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>
#include <vector>

#include "trace/osmesa/gl_state.h"
#include "osmesa/osmesa_harness.h"
#include "gl/lighting.h"
#include "gl/render_state.h"
#include "shadow/facing.h"
#include "shadow/light_shadow.h"
#include "shadow/light_view.h"
#include "shadow/scene_passes.h"
#include "shadow/scene_view.h"
#include "shadow/shadow_volume.h"
#include "shadow/soft_lights.h"
#include "shadow/stencil_counting.h"
#include "shadow/volume_renderer.h"

namespace shadowref::bench {

namespace {

// GL 1.5+ entry points (gl.h declares GL 1.1 only), loaded by conformance::loadGlFunction.
struct GlFunctions {
  PFNGLCREATESHADERPROC createShader = nullptr;
  PFNGLSHADERSOURCEPROC shaderSource = nullptr;
  PFNGLCOMPILESHADERPROC compileShader = nullptr;
  PFNGLGETSHADERIVPROC getShaderiv = nullptr;
  PFNGLGETSHADERINFOLOGPROC getShaderInfoLog = nullptr;
  PFNGLDELETESHADERPROC deleteShader = nullptr;
  PFNGLCREATEPROGRAMPROC createProgram = nullptr;
  PFNGLATTACHSHADERPROC attachShader = nullptr;
  PFNGLLINKPROGRAMPROC linkProgram = nullptr;
  PFNGLGETPROGRAMIVPROC getProgramiv = nullptr;
  PFNGLGETPROGRAMINFOLOGPROC getProgramInfoLog = nullptr;
  PFNGLDELETEPROGRAMPROC deleteProgram = nullptr;
  PFNGLUSEPROGRAMPROC useProgram = nullptr;
  PFNGLGETUNIFORMLOCATIONPROC getUniformLocation = nullptr;
  PFNGLUNIFORM1IPROC uniform1i = nullptr;
  PFNGLUNIFORM1FPROC uniform1f = nullptr;
  PFNGLUNIFORM3FPROC uniform3f = nullptr;
  PFNGLUNIFORM1FVPROC uniform1fv = nullptr;
  PFNGLUNIFORM3FVPROC uniform3fv = nullptr;
  PFNGLUNIFORM4FVPROC uniform4fv = nullptr;
  PFNGLUNIFORMMATRIX3FVPROC uniformMatrix3fv = nullptr;
  PFNGLUNIFORMMATRIX4FVPROC uniformMatrix4fv = nullptr;
  conformance::GlStencilFunctions stencil;
  PFNGLGENBUFFERSPROC genBuffers = nullptr;
  PFNGLDELETEBUFFERSPROC deleteBuffers = nullptr;
  PFNGLBINDBUFFERPROC bindBuffer = nullptr;
  PFNGLBUFFERDATAPROC bufferData = nullptr;
  PFNGLGENFRAMEBUFFERSPROC genFramebuffers = nullptr;
  PFNGLDELETEFRAMEBUFFERSPROC deleteFramebuffers = nullptr;
  PFNGLBINDFRAMEBUFFERPROC bindFramebuffer = nullptr;
  PFNGLFRAMEBUFFERTEXTURE2DPROC framebufferTexture2D = nullptr;
  PFNGLCHECKFRAMEBUFFERSTATUSPROC checkFramebufferStatus = nullptr;
};

GlFunctions loadFunctions() {
  GlFunctions gl;
  gl.stencil = conformance::GlStencilFunctions::load();
  gl.genBuffers = conformance::loadGlFunction<PFNGLGENBUFFERSPROC>("glGenBuffers");
  gl.deleteBuffers = conformance::loadGlFunction<PFNGLDELETEBUFFERSPROC>("glDeleteBuffers");
  gl.bindBuffer = conformance::loadGlFunction<PFNGLBINDBUFFERPROC>("glBindBuffer");
  gl.bufferData = conformance::loadGlFunction<PFNGLBUFFERDATAPROC>("glBufferData");
  gl.genFramebuffers = conformance::loadGlFunction<PFNGLGENFRAMEBUFFERSPROC>("glGenFramebuffers");
  gl.deleteFramebuffers = conformance::loadGlFunction<PFNGLDELETEFRAMEBUFFERSPROC>("glDeleteFramebuffers");
  gl.bindFramebuffer = conformance::loadGlFunction<PFNGLBINDFRAMEBUFFERPROC>("glBindFramebuffer");
  gl.framebufferTexture2D = conformance::loadGlFunction<PFNGLFRAMEBUFFERTEXTURE2DPROC>("glFramebufferTexture2D");
  gl.checkFramebufferStatus = conformance::loadGlFunction<PFNGLCHECKFRAMEBUFFERSTATUSPROC>("glCheckFramebufferStatus");
  gl.createShader = conformance::loadGlFunction<PFNGLCREATESHADERPROC>("glCreateShader");
  gl.shaderSource = conformance::loadGlFunction<PFNGLSHADERSOURCEPROC>("glShaderSource");
  gl.compileShader = conformance::loadGlFunction<PFNGLCOMPILESHADERPROC>("glCompileShader");
  gl.getShaderiv = conformance::loadGlFunction<PFNGLGETSHADERIVPROC>("glGetShaderiv");
  gl.getShaderInfoLog = conformance::loadGlFunction<PFNGLGETSHADERINFOLOGPROC>("glGetShaderInfoLog");
  gl.deleteShader = conformance::loadGlFunction<PFNGLDELETESHADERPROC>("glDeleteShader");
  gl.createProgram = conformance::loadGlFunction<PFNGLCREATEPROGRAMPROC>("glCreateProgram");
  gl.attachShader = conformance::loadGlFunction<PFNGLATTACHSHADERPROC>("glAttachShader");
  gl.linkProgram = conformance::loadGlFunction<PFNGLLINKPROGRAMPROC>("glLinkProgram");
  gl.getProgramiv = conformance::loadGlFunction<PFNGLGETPROGRAMIVPROC>("glGetProgramiv");
  gl.getProgramInfoLog = conformance::loadGlFunction<PFNGLGETPROGRAMINFOLOGPROC>("glGetProgramInfoLog");
  gl.deleteProgram = conformance::loadGlFunction<PFNGLDELETEPROGRAMPROC>("glDeleteProgram");
  gl.useProgram = conformance::loadGlFunction<PFNGLUSEPROGRAMPROC>("glUseProgram");
  gl.getUniformLocation = conformance::loadGlFunction<PFNGLGETUNIFORMLOCATIONPROC>("glGetUniformLocation");
  gl.uniform1i = conformance::loadGlFunction<PFNGLUNIFORM1IPROC>("glUniform1i");
  gl.uniform1f = conformance::loadGlFunction<PFNGLUNIFORM1FPROC>("glUniform1f");
  gl.uniform3f = conformance::loadGlFunction<PFNGLUNIFORM3FPROC>("glUniform3f");
  gl.uniform1fv = conformance::loadGlFunction<PFNGLUNIFORM1FVPROC>("glUniform1fv");
  gl.uniform3fv = conformance::loadGlFunction<PFNGLUNIFORM3FVPROC>("glUniform3fv");
  gl.uniform4fv = conformance::loadGlFunction<PFNGLUNIFORM4FVPROC>("glUniform4fv");
  gl.uniformMatrix3fv = conformance::loadGlFunction<PFNGLUNIFORMMATRIX3FVPROC>("glUniformMatrix3fv");
  gl.uniformMatrix4fv = conformance::loadGlFunction<PFNGLUNIFORMMATRIX4FVPROC>("glUniformMatrix4fv");
  return gl;
}

void color4(GLenum face, GLenum what, const glm::dvec3& c) {
  const GLfloat v[4] = {GLfloat(c.r), GLfloat(c.g), GLfloat(c.b), 1.0f};
  glMaterialfv(face, what, v);
}

void setMaterial(const Material& m) {
  color4(GL_FRONT_AND_BACK, GL_AMBIENT, m.ambient);
  color4(GL_FRONT_AND_BACK, GL_DIFFUSE, m.diffuse);
  color4(GL_FRONT_AND_BACK, GL_SPECULAR, m.specular);
  color4(GL_FRONT_AND_BACK, GL_EMISSION, glm::dvec3(0.0));
  glMaterialf(GL_FRONT_AND_BACK, GL_SHININESS, GLfloat(std::clamp(m.shininess, 0.0, 128.0)));
}

void setGlobalAmbient(const glm::dvec3& a) {
  const GLfloat v[4] = {GLfloat(a.r), GLfloat(a.g), GLfloat(a.b), 1.0f};
  glLightModelfv(GL_LIGHT_MODEL_AMBIENT, v);
}

// GL light `slot` as the scene's light; the modelview must be the camera's view matrix, so the
// position and spot direction are given in world space (GL stores them in eye space).
void setLight(int slot, const Light& light) {
  const GLenum id = GLenum(GL_LIGHT0 + slot);
  const glm::dvec4 p = light.homogeneous();
  const GLfloat position[4] = {GLfloat(p.x), GLfloat(p.y), GLfloat(p.z), GLfloat(p.w)};
  const GLfloat zero[4] = {0, 0, 0, 1};
  const GLfloat c[4] = {GLfloat(light.color.r), GLfloat(light.color.g), GLfloat(light.color.b), 1.0f};
  glLightfv(id, GL_POSITION, position);
  glLightfv(id, GL_AMBIENT, zero);
  glLightfv(id, GL_DIFFUSE, c);
  glLightfv(id, GL_SPECULAR, c);
  const bool directional = light.type == LightType::Directional;
  glLightf(id, GL_CONSTANT_ATTENUATION, directional ? 1.0f : GLfloat(light.attenuation.x));
  glLightf(id, GL_LINEAR_ATTENUATION, directional ? 0.0f : GLfloat(light.attenuation.y));
  glLightf(id, GL_QUADRATIC_ATTENUATION, directional ? 0.0f : GLfloat(light.attenuation.z));
  if (light.type == LightType::Spot) {
    const GLfloat d[3] = {GLfloat(light.direction.x), GLfloat(light.direction.y), GLfloat(light.direction.z)};
    glLightfv(id, GL_SPOT_DIRECTION, d);
    glLightf(id, GL_SPOT_CUTOFF, GLfloat(std::min(light.spotCutoffDegrees, 90.0)));
    glLightf(id, GL_SPOT_EXPONENT, GLfloat(std::clamp(light.spotExponent, 0.0, 128.0)));
  } else {
    glLightf(id, GL_SPOT_CUTOFF, 180.0f);
  }
  glEnable(id);
}

void disableLights() {
  for (int i = 0; i < 8; ++i) glDisable(GLenum(GL_LIGHT0 + i));
}

void loadMatrix(GLenum mode, const glm::dmat4& m) {
  glMatrixMode(mode);
  glLoadMatrixd(&m[0][0]);  // glm is column-major like GL
}

// shadowref's per-pixel Phong model (gl/lighting.cpp lightContribution, PerPixelLightingShader,
// and shadow_map_renderer.cpp ShadowMappedShader) in GLSL 1.20, in float. Everything that does not
// depend on the fragment comes from lightTerms, computed in double on the CPU per draw exactly as
// shadowref does, so only the per-fragment arithmetic is GL's. The world position and normal are
// interpolated (the normal normalised per vertex first, as prepareInstances does); the position
// goes through ftransform() so the depth values are those of the fixed-function volume passes.
// One program per number of lights (0 to 8) and per frame kind (shadow-mapped or not), as a GL
// application would specialise them: with the count a compile-time constant the loop unrolls to
// constant array indices and the shadow branch goes, where one program with a loop to a uniform
// count took llvmpipe more than twice as long (room: 36 against 16 ms per frame).
constexpr int kMaxLights = 8;

constexpr const char* kVertexShader = R"(#version 120
uniform mat4 world;
uniform mat3 normalMatrix;
varying vec3 worldPosition;
varying vec3 worldNormal;
void main() {
  worldPosition = (world * gl_Vertex).xyz;
  worldNormal = normalize(normalMatrix * gl_Normal);
  gl_Position = ftransform();
}
)";

// Lights as lightTerms gives them: position.w = 0 directional (xyz the unit vector towards the
// light), 1 point or spot; spot.w is the cosine of the cutoff, -2 for a light that is no spot.
// Compiled after "#version 120" and the defines LIGHT_COUNT and SHADOW_MAPPED (0 or 1).
constexpr const char* kFragmentShader = R"(
uniform vec3 eye;
uniform vec3 ambient;
uniform vec4 lightPosition[8];
uniform vec3 lightAttenuation[8];
uniform vec4 lightSpot[8];
uniform float lightSpotExponent[8];
uniform vec3 lightDiffuse[8];
uniform vec3 lightSpecular[8];
uniform bool specular;
uniform bool blinn;
uniform float shininess;
uniform sampler2DShadow shadowMap;
uniform mat4 shadowMatrix;
uniform float compareFail;
varying vec3 worldPosition;
varying vec3 worldNormal;

vec3 lightContribution(int i, vec3 p, vec3 n) {
  vec3 l;
  float attenuation = 1.0;
  if (lightPosition[i].w == 0.0) {
    l = lightPosition[i].xyz;
  } else {
    vec3 toLight = lightPosition[i].xyz - p;
    float d = length(toLight);
    if (d == 0.0) return vec3(0.0);
    l = toLight / d;
    vec3 a = lightAttenuation[i];
    attenuation = 1.0 / (a.x + a.y * d + a.z * d * d);
    if (lightSpot[i].w > -1.5) {
      float cosAngle = dot(-l, lightSpot[i].xyz);
      if (cosAngle < lightSpot[i].w) return vec3(0.0);
      // pow(x, 0) is 1 in C even for x = 0; GLSL leaves pow(0, 0) undefined.
      if (lightSpotExponent[i] != 0.0) attenuation *= pow(max(cosAngle, 0.0), lightSpotExponent[i]);
    }
  }
  float nDotL = dot(n, l);
  if (nDotL <= 0.0) return vec3(0.0);
  vec3 color = lightDiffuse[i] * nDotL;
  if (specular) {
    vec3 v = normalize(eye - p);
    float s = blinn ? max(dot(n, normalize(l + v)), 0.0) : max(dot(2.0 * nDotL * n - l, v), 0.0);
    // pow(0, n) is 0 in C; GLSL computes pow through log2, keep 0 out of it.
    color += lightSpecular[i] * (shininess == 0.0 ? 1.0 : s > 0.0 ? pow(s, shininess) : 0.0);
  }
  return attenuation * color;
}

void main() {
  vec3 n = worldNormal;
  float len = length(n);
  if (len > 0.0) n = n / len;
  if (!gl_FrontFacing) n = -n;  // two-sided: a back face is lit with the normal flipped
  vec3 color = ambient;
  for (int i = 0; i < LIGHT_COUNT; ++i) color += lightContribution(i, worldPosition, n);
#if SHADOW_MAPPED
  // strq = T . world position; the texture's compare mode gives 1 for r/q <= D. Behind a
  // perspective light (q <= 0) shadowref's lookup says lit.
  vec4 strq = shadowMatrix * vec4(worldPosition, 1.0);
  float lit = shadow2DProj(shadowMap, strq).r;
  color *= strq.q > 0.0 ? mix(compareFail, 1.0, lit) : 1.0;
#endif
  gl_FragColor = vec4(color, 1.0);
}
)";

GLuint compileShader(const GlFunctions& gl, GLenum type, const std::string& source) {
  const GLuint shader = gl.createShader(type);
  const char* text = source.c_str();
  gl.shaderSource(shader, 1, &text, nullptr);
  gl.compileShader(shader);
  GLint ok = GL_FALSE;
  gl.getShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    gl.getShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::string log(size_t(std::max(length, 1)), '\0');
    gl.getShaderInfoLog(shader, GLsizei(log.size()), nullptr, log.data());
    gl.deleteShader(shader);
    const char* kind = type == GL_VERTEX_SHADER ? "vertex" : "fragment";
    throw std::runtime_error(std::string("vs-mesa: the per-pixel ") + kind + " shader does not compile:\n" +
                             log.c_str());
  }
  return shader;
}

// The per-pixel program and its uniform locations (-1 for one the compiler dropped: glUniform
// ignores it).
struct PerPixelProgram {
  GLuint program = 0;
  GLint world = -1, normalMatrix = -1, eye = -1, ambient = -1, lightPosition = -1, lightAttenuation = -1,
        lightSpot = -1, lightSpotExponent = -1, lightDiffuse = -1, lightSpecular = -1, specular = -1, blinn = -1,
        shininess = -1, shadowMap = -1, shadowMatrix = -1, compareFail = -1;
};

PerPixelProgram buildPerPixelProgram(const GlFunctions& gl, int lightCount, bool shadowMapped) {
  const GLuint vs = compileShader(gl, GL_VERTEX_SHADER, kVertexShader);
  GLuint fs = 0;
  try {
    fs = compileShader(gl, GL_FRAGMENT_SHADER,
                       "#version 120\n#define LIGHT_COUNT " + std::to_string(lightCount) + "\n#define SHADOW_MAPPED " +
                           (shadowMapped ? "1" : "0") + "\n" + kFragmentShader);
  } catch (...) {
    gl.deleteShader(vs);
    throw;
  }
  PerPixelProgram p;
  p.program = gl.createProgram();
  gl.attachShader(p.program, vs);
  gl.attachShader(p.program, fs);
  gl.linkProgram(p.program);
  gl.deleteShader(vs);  // flagged only: deleted with the program
  gl.deleteShader(fs);
  GLint ok = GL_FALSE;
  gl.getProgramiv(p.program, GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    gl.getProgramiv(p.program, GL_INFO_LOG_LENGTH, &length);
    std::string log(size_t(std::max(length, 1)), '\0');
    gl.getProgramInfoLog(p.program, GLsizei(log.size()), nullptr, log.data());
    gl.deleteProgram(p.program);
    throw std::runtime_error(std::string("vs-mesa: the per-pixel program does not link:\n") + log.c_str());
  }
  auto at = [&](const char* name) { return gl.getUniformLocation(p.program, name); };
  p.world = at("world");
  p.normalMatrix = at("normalMatrix");
  p.eye = at("eye");
  p.ambient = at("ambient");
  p.lightPosition = at("lightPosition");
  p.lightAttenuation = at("lightAttenuation");
  p.lightSpot = at("lightSpot");
  p.lightSpotExponent = at("lightSpotExponent");
  p.lightDiffuse = at("lightDiffuse");
  p.lightSpecular = at("lightSpecular");
  p.specular = at("specular");
  p.blinn = at("blinn");
  p.shininess = at("shininess");
  p.shadowMap = at("shadowMap");
  p.shadowMatrix = at("shadowMatrix");
  p.compareFail = at("compareFail");
  return p;
}

void uniformMatrix(const GlFunctions& gl, GLint location, const glm::dmat4& m) {
  const glm::mat4 f(m);
  gl.uniformMatrix4fv(location, 1, GL_FALSE, &f[0][0]);  // column-major, like glm
}

void uniformMatrix(const GlFunctions& gl, GLint location, const glm::dmat3& m) {
  const glm::mat3 f(m);
  gl.uniformMatrix3fv(location, 1, GL_FALSE, &f[0][0]);
}

void uniformVec3(const GlFunctions& gl, GLint location, const glm::dvec3& v) {
  gl.uniform3f(location, GLfloat(v.x), GLfloat(v.y), GLfloat(v.z));
}

// A mesh in vertex buffers (float, as a GL application would keep it): the render view with
// normals for the scene passes, or positions only (the shadow mesh for the map pass).
struct MeshBuffers {
  GLuint positions = 0, normals = 0, indices = 0;
  GLsizei indexCount = 0;
};

MeshBuffers upload(const GlFunctions& gl, const Mesh& mesh, bool withNormals) {
  MeshBuffers b;
  std::vector<GLfloat> data;
  auto floats = [&](const std::vector<glm::dvec3>& v) {
    data.clear();
    for (const glm::dvec3& p : v) data.insert(data.end(), {GLfloat(p.x), GLfloat(p.y), GLfloat(p.z)});
  };
  gl.genBuffers(1, &b.positions);
  floats(mesh.positions);
  gl.bindBuffer(GL_ARRAY_BUFFER, b.positions);
  gl.bufferData(GL_ARRAY_BUFFER, GLsizeiptr(data.size() * sizeof(GLfloat)), data.data(), GL_STATIC_DRAW);
  if (withNormals) {
    gl.genBuffers(1, &b.normals);
    floats(mesh.normals);
    gl.bindBuffer(GL_ARRAY_BUFFER, b.normals);
    gl.bufferData(GL_ARRAY_BUFFER, GLsizeiptr(data.size() * sizeof(GLfloat)), data.data(), GL_STATIC_DRAW);
  }
  gl.genBuffers(1, &b.indices);
  gl.bindBuffer(GL_ELEMENT_ARRAY_BUFFER, b.indices);
  gl.bufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(mesh.triangles.size() * sizeof(glm::uvec3)), mesh.triangles.data(),
                GL_STATIC_DRAW);
  b.indexCount = GLsizei(mesh.triangles.size() * 3);
  gl.bindBuffer(GL_ARRAY_BUFFER, 0);
  gl.bindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
  return b;
}

}  // namespace

struct MesaFrameRenderer::Impl {
  const Scene& scene;
  std::string method;
  MesaLighting lighting;
  GlFunctions gl;
  std::array<PerPixelProgram, kMaxLights + 1> programs;  // by number of lights
  glm::dmat4 shadowMatrix{1.0};                          // T of the shadow-map camera pass, as given
  SceneView view;
  std::vector<Instance> instances;
  std::vector<MeshBuffers> render, shadow;  // per instance
  std::vector<Light> lights;                 // soft lights expanded, as volume_renderer.cpp does
  ShadowVolume volume;
  ShadowVolumeWorkspace workspace;
  GLuint mapTexture = 0, mapFramebuffer = 0;

  Impl(const Scene& s, std::string_view m, MesaLighting shading) : scene(s), method(m), lighting(shading) {
    // The harness's context of the scene's size (the product's OSMesa context), left current:
    // every call below goes to it.
    conformance::mesaContext(scene.width, scene.height);
    gl = loadFunctions();
    const bool volumes = method == "zpass" || method == "zfail";
    if (!volumes && method != "shadowmap")
      throw std::runtime_error(std::string("vs-mesa: the GL side draws zpass, zfail and shadowmap, not ") + method);
    view = makeCameraView(scene, volumes);
    instances = scene.instances();
    for (const Instance& inst : instances) {
      render.push_back(upload(gl, *inst.mesh, true));
      shadow.push_back(inst.shadowMesh ? upload(gl, *inst.shadowMesh, false) : MeshBuffers{});
    }
    for (const Light& light : scene.lights)
      for (const Light& l : expandSoftLight(light)) lights.push_back(l);
    if (method == "shadowmap") createShadowMap();
    // All nine now: a shader error is reported here, before any frame (an exception out of a frame
    // left Mesa crashing in OSMesaDestroyContext at exit), and no frame pays for a compile.
    if (lighting == MesaLighting::PerPixel)
      for (int k = 0; k <= kMaxLights; ++k) buildProgram(k);

    glDisable(GL_DITHER);
    glShadeModel(GL_SMOOTH);
    glEnable(GL_NORMALIZE);
    glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, GL_TRUE);  // shadowref lights back faces with -N
    glLightModeli(GL_LIGHT_MODEL_LOCAL_VIEWER, GL_TRUE);
    glEnableClientState(GL_VERTEX_ARRAY);
  }

  ~Impl() {
    for (auto* list : {&render, &shadow})
      for (MeshBuffers& b : *list) {
        const GLuint names[3] = {b.positions, b.normals, b.indices};
        gl.deleteBuffers(3, names);
      }
    if (mapFramebuffer) gl.deleteFramebuffers(1, &mapFramebuffer);
    if (mapTexture) glDeleteTextures(1, &mapTexture);
    for (const PerPixelProgram& p : programs)
      if (p.program) gl.deleteProgram(p.program);
  }

  void createShadowMap() {
    for (const Light& l : lights)
      if (l.type == LightType::Point)
        throw std::runtime_error("vs-mesa: the GL side has no cube shadow maps (point light '" + l.name + "')");
    if (lights.size() != 1) throw std::runtime_error("vs-mesa: the GL shadow-map frame takes exactly one light");
    const int size = scene.shadow.mapSize;
    glGenTextures(1, &mapTexture);
    glBindTexture(GL_TEXTURE_2D, mapTexture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, size, size, 0, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_R_TO_TEXTURE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    glTexParameteri(GL_TEXTURE_2D, GL_DEPTH_TEXTURE_MODE, GL_LUMINANCE);
    gl.genFramebuffers(1, &mapFramebuffer);
    gl.bindFramebuffer(GL_FRAMEBUFFER, mapFramebuffer);
    gl.framebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, mapTexture, 0);
    glDrawBuffer(GL_NONE);
    glReadBuffer(GL_NONE);
    if (gl.checkFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw std::runtime_error("vs-mesa: the shadow-map framebuffer object is incomplete");
    gl.bindFramebuffer(GL_FRAMEBUFFER, 0);
    glBindTexture(GL_TEXTURE_2D, 0);
  }

  // Draws instance i's render mesh (with normals when lit) or its shadow mesh.
  void drawMesh(const MeshBuffers& b, const RenderState& state, const Instance& inst, bool withNormals) {
    RenderState mirrored;
    conformance::applyRenderState(stateFor(state, inst, mirrored), gl.stencil);
    gl.bindBuffer(GL_ARRAY_BUFFER, b.positions);
    glVertexPointer(3, GL_FLOAT, 0, nullptr);
    if (withNormals) {
      glEnableClientState(GL_NORMAL_ARRAY);
      gl.bindBuffer(GL_ARRAY_BUFFER, b.normals);
      glNormalPointer(GL_FLOAT, 0, nullptr);
    } else {
      glDisableClientState(GL_NORMAL_ARRAY);
    }
    gl.bindBuffer(GL_ELEMENT_ARRAY_BUFFER, b.indices);
    glDrawElements(GL_TRIANGLES, b.indexCount, GL_UNSIGNED_INT, nullptr);
    gl.bindBuffer(GL_ARRAY_BUFFER, 0);
    gl.bindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
  }

  // drawLit of scene_passes.cpp: every instance lit by `lit` (those in range), ambient or not.
  // Per pixel, the program draws every per-pixel material, and in the shadow-map camera pass every
  // material (shadowref's camera pass lights a Gouraud material per vertex; the per-pixel pairs of
  // bench/vs-mesa draw scenes whose shadow-mapped materials are all per pixel).
  void drawLitPass(const RenderState& state, const std::vector<const Light*>& lit, bool includeAmbient) {
    const bool shadowMapped = method == "shadowmap";
    glEnable(GL_LIGHTING);
    setGlobalAmbient(includeAmbient ? scene.ambient : glm::dvec3(0.0));
    const PerPixelProgram* bound = nullptr;  // nullptr: fixed function
    std::vector<const Light*> inRange;
    for (size_t i = 0; i < instances.size(); ++i) {
      const Instance& inst = instances[i];
      inRange.clear();
      for (const Light* l : lit)
        if (withinRange(*l, inst.worldBounds) && inRange.size() < size_t(kMaxLights)) inRange.push_back(l);
      if (!includeAmbient && inRange.empty()) continue;
      const Material& material = scene.materials.at(size_t(inst.material));
      const bool programmed =
          lighting == MesaLighting::PerPixel && (shadowMapped || material.shading == ShadingModel::PerPixel);
      const PerPixelProgram* wanted = programmed ? &program(int(inRange.size())) : nullptr;
      if (wanted != bound) {
        gl.useProgram(wanted ? wanted->program : 0);
        bound = wanted;
      }
      if (programmed) drawPerPixel(*bound, i, state, inRange, includeAmbient);
      else drawFixedFunction(i, state, inRange);
    }
    if (bound) gl.useProgram(0);
    glDisable(GL_LIGHTING);
  }

  // The per-pixel program for `lightCount` lights, with the uniforms that stay for the renderer's
  // life: the camera, the sampler's unit, the compare-fail value.
  void buildProgram(int lightCount) {
    PerPixelProgram& p = programs.at(size_t(lightCount));
    p = buildPerPixelProgram(gl, lightCount, method == "shadowmap");
    gl.useProgram(p.program);
    uniformVec3(gl, p.eye, view.eye);
    gl.uniform1i(p.shadowMap, 0);  // texture unit 0
    gl.uniform1f(p.compareFail, GLfloat(scene.shadow.compareFail));
    uniformMatrix(gl, p.shadowMatrix, shadowMatrix);
    gl.useProgram(0);
  }

  const PerPixelProgram& program(int lightCount) const { return programs.at(size_t(lightCount)); }

  // T into every program, when it changed (the first frame: the light and the scene stay).
  void setShadowMatrix(const glm::dmat4& t) {
    if (t == shadowMatrix) return;
    shadowMatrix = t;
    for (const PerPixelProgram& p : programs) {
      gl.useProgram(p.program);
      uniformMatrix(gl, p.shadowMatrix, t);
    }
    gl.useProgram(0);
  }

  void drawFixedFunction(size_t i, const RenderState& state, const std::vector<const Light*>& inRange) {
    const Instance& inst = instances[i];
    loadMatrix(GL_MODELVIEW, view.view);
    disableLights();
    int slot = 0;
    for (const Light* l : inRange) setLight(slot++, *l);
    setMaterial(scene.materials.at(size_t(inst.material)));
    loadMatrix(GL_MODELVIEW, view.view * inst.world);
    drawMesh(render[i], state, inst, true);
  }

  // The uniforms of one draw: the instance's matrices, the ambient term and the lights' terms as
  // drawLit gives them to PerPixelLightingShader (toPhongMaterial, toPhongLight, lightTerms).
  void drawPerPixel(const PerPixelProgram& perPixel, size_t i, const RenderState& state,
                    const std::vector<const Light*>& inRange, bool includeAmbient) {
    const Instance& inst = instances[i];
    const PhongMaterial material = toPhongMaterial(scene.materials.at(size_t(inst.material)));
    uniformMatrix(gl, perPixel.world, inst.world);
    uniformMatrix(gl, perPixel.normalMatrix, glm::transpose(glm::inverse(glm::dmat3(inst.world))));
    uniformVec3(gl, perPixel.ambient, includeAmbient ? ambientTerm(material, scene.ambient) : glm::dvec3(0.0));
    GLfloat position[4 * kMaxLights] = {}, attenuation[3 * kMaxLights] = {}, spot[4 * kMaxLights] = {},
            exponent[kMaxLights] = {}, diffuse[3 * kMaxLights] = {}, specular[3 * kMaxLights] = {};
    const int count = int(inRange.size());
    for (int k = 0; k < count; ++k) {
      const LightTerms t = lightTerms(toPhongLight(*inRange[size_t(k)]), material);
      const glm::dvec4 p = t.directional ? glm::dvec4(t.direction, 0.0) : glm::dvec4(t.point, 1.0);
      const glm::dvec4 sp = t.spot ? glm::dvec4(t.spotAxis, t.spotCosCutoff) : glm::dvec4(0.0, 0.0, 0.0, -2.0);
      for (int c = 0; c < 4; ++c) {
        position[4 * k + c] = GLfloat(p[c]);
        spot[4 * k + c] = GLfloat(sp[c]);
      }
      for (int c = 0; c < 3; ++c) {
        attenuation[3 * k + c] = GLfloat(t.attenuation[c]);
        diffuse[3 * k + c] = GLfloat(t.diffuse[c]);
        specular[3 * k + c] = GLfloat(t.specularColor[c]);
      }
      exponent[k] = GLfloat(t.spotExponent);
    }
    if (count > 0) {
      gl.uniform4fv(perPixel.lightPosition, count, position);
      gl.uniform3fv(perPixel.lightAttenuation, count, attenuation);
      gl.uniform4fv(perPixel.lightSpot, count, spot);
      gl.uniform1fv(perPixel.lightSpotExponent, count, exponent);
      gl.uniform3fv(perPixel.lightDiffuse, count, diffuse);
      gl.uniform3fv(perPixel.lightSpecular, count, specular);
    }
    // lightTerms' specular flag is the material's (ks != 0), the same for every light.
    gl.uniform1i(perPixel.specular, material.specular != glm::dvec3(0.0) ? 1 : 0);
    gl.uniform1i(perPixel.blinn, material.blinn ? 1 : 0);
    gl.uniform1f(perPixel.shininess, GLfloat(material.shininess));
    loadMatrix(GL_MODELVIEW, view.view * inst.world);  // ftransform()
    drawMesh(render[i], state, inst, true);
  }

  void drawVolumeParts(const RenderState& state, const Instance& inst) {
    RenderState mirrored;
    conformance::applyRenderState(stateFor(state, inst, mirrored), gl.stencil);
    glVertexPointer(4, GL_DOUBLE, 0, volume.positions.data());
    for (VolumePart part : {VolumePart::Side, VolumePart::FrontCap, VolumePart::BackCap}) {
      const std::vector<glm::uvec3>& t = volume.part(part);
      if (!t.empty()) glDrawElements(GL_TRIANGLES, GLsizei(t.size() * 3), GL_UNSIGNED_INT, t.data());
    }
  }

  // Step 2 of volume_renderer.cpp: every caster's volume, rebuilt for this light this frame.
  void drawVolumePass(const RenderState& base, const Light& light) {
    const StencilCounting how = method == "zfail" ? StencilCounting::ZFail : StencilCounting::ZPass;
    const std::vector<RenderState> states =
        volumePassStates(base, how, CountingOptions{scene.shadow.twoSidedStencil, scene.shadow.wrapOps});
    glDisableClientState(GL_NORMAL_ARRAY);
    for (const Instance& inst : instances) {
      if (!inst.shadowMesh || !withinRange(light, inst.shadowBounds)) continue;
      buildShadowVolume(*inst.shadowMesh, lightInObjectSpace(inst.world, light.homogeneous()), scene.shadow.silhouette,
                        how == StencilCounting::ZFail, volume, &workspace);
      loadMatrix(GL_MODELVIEW, view.view * inst.world);
      for (const RenderState& s : states) drawVolumeParts(s, inst);
    }
  }

  void renderVolumes() {
    loadMatrix(GL_PROJECTION, view.projection);
    const RenderState base = volumeBaseState(view);
    conformance::applyRenderState(base, gl.stencil);
    glClearColor(GLfloat(scene.background.r), GLfloat(scene.background.g), GLfloat(scene.background.b), 1.0f);
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    drawLitPass(base, {}, true);

    RenderState composite = base;
    composite.depthFunc = CompareFunc::LEqual;
    composite.depthWrite = false;
    composite.stencilTest = true;
    for (StencilFaceState& s : composite.stencil) {
      s.func = CompareFunc::Equal;
      s.ref = 0;
    }
    composite.blend = {true, BlendFactor::One, BlendFactor::One};
    for (const Light& light : lights) {
      conformance::applyRenderState(base, gl.stencil);
      glClearStencil(0);
      glClear(GL_STENCIL_BUFFER_BIT);
      drawVolumePass(base, light);
      drawLitPass(composite, {&light}, false);
    }
  }

  void renderShadowMap() {
    const Light& light = lights.front();
    // The same light view as shadowref's map (fitted to the casters where the scene says so), and
    // its lookup of points outside a fitted map as lit: the border's depth 1 passes LEQUAL.
    const StandardMapView standard = standardMapView(scene, instances, view, light, worldBounds(instances));
    const LightView& lv = standard.view;
    glBindTexture(GL_TEXTURE_2D, mapTexture);
    const GLint wrap = standard.fittedToCasters ? GL_CLAMP_TO_BORDER : GL_CLAMP_TO_EDGE;
    const GLfloat border[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    glTexParameterfv(GL_TEXTURE_2D, GL_TEXTURE_BORDER_COLOR, border);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, wrap);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, wrap);
    glBindTexture(GL_TEXTURE_2D, 0);
    const int size = scene.shadow.mapSize;
    // Step 1: depth from the light (shadow_map_renderer.cpp renderDepthMap).
    RenderState map;
    map.viewport = Viewport{0, 0, size, size, 0.0, 1.0};
    map.depthTest = true;
    map.depthFunc = CompareFunc::Less;
    map.colorMask = {false, false, false, false};
    map.cull = scene.shadow.backFacesOnly ? CullMode::Front : CullMode::None;
    map.polygonOffset = {scene.shadow.offsetFactor != 0.0 || scene.shadow.offsetUnits != 0.0, scene.shadow.offsetFactor,
                         scene.shadow.offsetUnits};
    gl.bindFramebuffer(GL_FRAMEBUFFER, mapFramebuffer);
    conformance::applyRenderState(map, gl.stencil);
    glClearDepth(1.0);
    glClear(GL_DEPTH_BUFFER_BIT);
    loadMatrix(GL_PROJECTION, lv.projection);
    glDisableClientState(GL_NORMAL_ARRAY);
    for (size_t i = 0; i < instances.size(); ++i) {
      const Instance& inst = instances[i];
      if (!inst.shadowMesh || !withinRange(light, inst.shadowBounds)) continue;
      loadMatrix(GL_MODELVIEW, lv.view * inst.world);
      drawMesh(shadow[i], map, inst, false);
    }
    gl.bindFramebuffer(GL_FRAMEBUFFER, 0);

    // Step 2: the camera pass, lit and modulated by the depth compare through T = bias · P · V
    // applied to world positions: EYE_LINEAR texgen with identity planes given under the camera's
    // view matrix yields world coordinates.
    RenderState camera;
    camera.viewport = view.viewport;
    camera.cull = CullMode::Back;
    camera.depthTest = true;
    camera.depthFunc = CompareFunc::Less;
    conformance::applyRenderState(camera, gl.stencil);
    glClearColor(GLfloat(scene.background.r), GLfloat(scene.background.g), GLfloat(scene.background.b), 1.0f);
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    loadMatrix(GL_PROJECTION, view.projection);
    glBindTexture(GL_TEXTURE_2D, mapTexture);
    if (lighting == MesaLighting::PerPixel) {
      // The program does the lookup itself, with T as a uniform on its world position.
      setShadowMatrix(textureMatrix(lv));
      drawLitPass(camera, {&light}, true);
      return;
    }
    loadMatrix(GL_TEXTURE, textureMatrix(lv));
    loadMatrix(GL_MODELVIEW, view.view);
    const GLenum coords[4] = {GL_S, GL_T, GL_R, GL_Q};
    const GLenum gens[4] = {GL_TEXTURE_GEN_S, GL_TEXTURE_GEN_T, GL_TEXTURE_GEN_R, GL_TEXTURE_GEN_Q};
    for (int k = 0; k < 4; ++k) {
      GLdouble plane[4] = {0, 0, 0, 0};
      plane[k] = 1.0;
      glTexGeni(coords[k], GL_TEXTURE_GEN_MODE, GL_EYE_LINEAR);
      glTexGendv(coords[k], GL_EYE_PLANE, plane);
      glEnable(gens[k]);
    }
    glEnable(GL_TEXTURE_2D);
    glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
    drawLitPass(camera, {&light}, true);
    glDisable(GL_TEXTURE_2D);
    for (GLenum g : gens) glDisable(g);
    loadMatrix(GL_TEXTURE, glm::dmat4(1.0));
  }
};

const char* lightingName(MesaLighting lighting) {
  return lighting == MesaLighting::PerPixel ? "perpixel" : "fixed";
}

MesaFrameRenderer::MesaFrameRenderer(const Scene& scene, std::string_view method, MesaLighting lighting)
    : impl_(std::make_unique<Impl>(scene, method, lighting)) {}

MesaFrameRenderer::~MesaFrameRenderer() = default;

void MesaFrameRenderer::render() {
  if (impl_->method == "shadowmap") impl_->renderShadowMap();
  else impl_->renderVolumes();
  glFinish();
  if (glGetError() != GL_NO_ERROR) throw std::runtime_error("vs-mesa: GL error in the frame");
}

Framebuffer MesaFrameRenderer::readColor() const {
  const Scene& scene = impl_->scene;
  Framebuffer fb(scene.width, scene.height);
  fb.ensureColor();
  std::vector<unsigned char> rgba(size_t(scene.width) * size_t(scene.height) * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, scene.width, scene.height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  for (size_t i = 0; i < fb.color().size(); ++i)
    fb.color()[i] = glm::vec4(rgba[4 * i], rgba[4 * i + 1], rgba[4 * i + 2], rgba[4 * i + 3]) / 255.0f;
  return fb;
}

}  // namespace shadowref::bench
