#include "vtkMCXXRayDisplayPrivate.h"

#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderUtilities.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <string>

namespace
{
// Maps a line integral to a grey value g (window and level), and composites
// it as emitted light or, inverted, as a transmission factor.
const char* DisplayShaderDeclarations = R"(
uniform sampler2D lineIntegrals;
uniform float lowest;
uniform float inverseWindow;
uniform int invert;
uniform float imageDepth;
)";
const char* DisplayShaderBody = R"(
  float g = clamp((texture(lineIntegrals, texCoord).r - lowest) * inverseWindow, 0.0, 1.0);
  if (invert == 1)
  {
    g = 1.0 - g;
  }
  gl_FragData[0] = vec4(g, g, g, 1.0);
  gl_FragDepth = imageDepth; // at the far plane: depth tests tell film from geometry in front
)";

// Blends g onto what is there: added, or inverted, multiplied as 1 - g.
void BlendAdditively(vtkOpenGLState* state, bool invert)
{
  state->vtkglEnable(GL_BLEND);
  if (invert)
  {
    state->vtkglBlendFuncSeparate(GL_ZERO, GL_SRC_COLOR, GL_ZERO, GL_ONE); // dst * (1 - g)
  }
  else
  {
    state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ZERO, GL_ONE); // dst + g
  }
}
}

vtkMCXXRayDisplay::vtkMCXXRayDisplay() = default;

vtkMCXXRayDisplay::~vtkMCXXRayDisplay() = default;

std::vector<float> vtkMCXXRayDisplay::ReadDepth(
  vtkOpenGLRenderWindow* window, int x0, int y0, int width, int height)
{
  std::vector<float> depth(static_cast<std::size_t>(width) * height);
  vtkOpenGLState* state = window->GetState();
  GLint samples = 0;
  glGetIntegerv(GL_SAMPLES, &samples);
  if (samples > 0)
  {
    // The render window knows how to resolve its multisampled buffer.
    vtkOpenGLState::ScopedglEnableDisable scissor(state, GL_SCISSOR_TEST);
    window->GetZbufferData(x0, y0, x0 + width - 1, y0 + height - 1, depth.data());
    return depth;
  }
  GLint drawFramebuffer = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &drawFramebuffer);
  state->PushReadFramebufferBinding();
  state->vtkglBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<unsigned int>(drawFramebuffer));
  state->vtkglPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(x0, y0, width, height, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
  state->PopReadFramebufferBinding();
  return depth;
}

bool vtkMCXXRayDisplay::HasImageIn(vtkOpenGLRenderWindow* window) const
{
  return this->Texture && this->Texture->GetContext() == window;
}

void vtkMCXXRayDisplay::Upload(
  vtkOpenGLRenderWindow* window, int width, int height, const float* values)
{
  if (!this->HasImageIn(window))
  {
    this->Texture = vtkSmartPointer<vtkTextureObject>::New();
    this->Texture->SetContext(window);
    this->Texture->SetMinificationFilter(vtkTextureObject::Nearest);
    this->Texture->SetMagnificationFilter(vtkTextureObject::Nearest);
    this->Texture->SetWrapS(vtkTextureObject::ClampToEdge);
    this->Texture->SetWrapT(vtkTextureObject::ClampToEdge);
  }
  this->Texture->Create2DFromRaw(static_cast<unsigned int>(width),
    static_cast<unsigned int>(height), 1, VTK_FLOAT, const_cast<float*>(values));
}

bool vtkMCXXRayDisplay::ReadyShader(vtkOpenGLRenderWindow* window)
{
  if (!this->Quad)
  {
    std::string fragment = vtkOpenGLRenderUtilities::GetFullScreenQuadFragmentShaderTemplate();
    vtkShaderProgram::Substitute(fragment, "//VTK::FSQ::Decl", DisplayShaderDeclarations);
    vtkShaderProgram::Substitute(fragment, "//VTK::FSQ::Impl", DisplayShaderBody);
    this->Quad.reset(new vtkOpenGLQuadHelper(window,
      vtkOpenGLRenderUtilities::GetFullScreenQuadVertexShader().c_str(), fragment.c_str(), ""));
  }
  else
  {
    window->GetShaderCache()->ReadyShaderProgram(this->Quad->Program);
  }
  return this->Quad->Program != nullptr;
}

// As film, the grey replaces the background where nothing opaque was drawn
// (the quad lies at the far plane and passes the depth test only there) and
// blends over the geometry elsewhere (when there is some); additive, it
// blends everywhere. For a depth compositor the image writes a depth just in
// front of the far plane where nothing opaque was drawn (a first pass there,
// additive ones too), so that the compositor keeps it against other
// processes' empty pixels.
bool vtkMCXXRayDisplay::Draw(
  vtkOpenGLRenderWindow* window, double lowest, double inverseWindow, const Blending& blending)
{
  if (!this->Texture || !this->ReadyShader(window))
  {
    return false;
  }
  vtkOpenGLState* state = window->GetState();
  vtkOpenGLState::ScopedglEnableDisable depthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable blend(state, GL_BLEND);
  vtkOpenGLState::ScopedglDepthMask depthMask(state);
  vtkOpenGLState::ScopedglDepthFunc depthFunction(state);
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFunction(state);
  state->vtkglDepthMask(GL_FALSE);
  this->Texture->Activate();
  vtkShaderProgram* program = this->Quad->Program;
  program->SetUniformi("lineIntegrals", this->Texture->GetTextureUnit());
  program->SetUniformf("lowest", static_cast<float>(lowest));
  program->SetUniformf("inverseWindow", static_cast<float>(inverseWindow));
  program->SetUniformi("invert", blending.Invert ? 1 : 0);
  const bool compositedByDepth = blending.CompositedByDepth;
  // 2^-20 in front of the far plane: distinct from it in a 24-bit depth buffer.
  program->SetUniformf("imageDepth", compositedByDepth ? 1.0f - 0x1p-20f : 1.0f);
  const bool whereEmptyFirst = blending.Film || compositedByDepth;
  if (whereEmptyFirst)
  {
    state->vtkglEnable(GL_DEPTH_TEST); // where the depth buffer is empty
    state->vtkglDepthFunc(GL_LEQUAL);
    state->vtkglDepthMask(compositedByDepth ? GL_TRUE : GL_FALSE);
    if (blending.Film)
    {
      state->vtkglDisable(GL_BLEND);
    }
    else
    {
      BlendAdditively(state, blending.Invert);
    }
    this->Quad->Render();
    state->vtkglDepthMask(GL_FALSE);
  }
  if (!whereEmptyFirst || blending.OverGeometry)
  {
    if (whereEmptyFirst)
    {
      state->vtkglDepthFunc(GL_GREATER); // the geometry's pixels
    }
    else
    {
      state->vtkglDisable(GL_DEPTH_TEST);
    }
    BlendAdditively(state, blending.Invert);
    this->Quad->Render();
  }
  this->Texture->Deactivate();
  return true;
}

void vtkMCXXRayDisplay::ReleaseGraphicsResources(vtkWindow* window)
{
  if (this->Texture)
  {
    this->Texture->ReleaseGraphicsResources(window);
    this->Texture = nullptr;
  }
  if (this->Quad)
  {
    this->Quad->ReleaseGraphicsResources(window);
    this->Quad.reset();
  }
}
