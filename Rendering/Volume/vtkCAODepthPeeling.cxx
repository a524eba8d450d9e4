#include "vtkCAODepthPeeling.h"

#include "vtkAbstractVolumeMapper.h"
#include "vtkDualDepthPeelingPass.h"
#include "vtkInformation.h"
#include "vtkInformationObjectBaseVectorKey.h"
#include "vtkOpenGLRenderPass.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkVolume.h"
#include "vtk_glew.h"

#include "caoGPULayout.h"

namespace vtkCAO
{
namespace
{
// The sampler names vtkDualDepthPeelingPass sets for a volume's program.
const char* const Samplers[5] = { "outerDepthTex", "innerDepthTex", "lastFrontColorTex",
  "opaqueDepthTex", "depthRangeTex" };

const char* const ProbeVS = "//VTK::System::Dec\n"
                            "in vec4 vertexMC;\n"
                            "void main() { gl_Position = vertexMC; }\n";
const char* const ProbeFS = "//VTK::System::Dec\n"
                            "//VTK::Output::Dec\n"
                            "uniform sampler2D outerDepthTex;\n"
                            "uniform sampler2D innerDepthTex;\n"
                            "uniform sampler2D lastFrontColorTex;\n"
                            "uniform sampler2D opaqueDepthTex;\n"
                            "uniform sampler2D depthRangeTex;\n"
                            "void main()\n"
                            "{\n"
                            "  vec2 c = vec2(0.5);\n"
                            "  gl_FragData[0] = texture(outerDepthTex, c) + texture(innerDepthTex, c) +\n"
                            "    texture(lastFrontColorTex, c) + texture(opaqueDepthTex, c) +\n"
                            "    texture(depthRangeTex, c);\n"
                            "}\n";

vtkDualDepthPeelingPass* PeelingPass(vtkVolume* volume)
{
  vtkInformation* keys = volume ? volume->GetPropertyKeys() : nullptr;
  if (!keys || !keys->Has(vtkOpenGLRenderPass::RenderPasses()))
    return nullptr;
  const int n = keys->Length(vtkOpenGLRenderPass::RenderPasses());
  for (int i = 0; i < n; ++i)
    if (auto* pass =
          vtkDualDepthPeelingPass::SafeDownCast(keys->Get(vtkOpenGLRenderPass::RenderPasses(), i)))
      return pass;
  return nullptr;
}

/// The stage, from the code the pass substitutes into its volume template.
int Stage(vtkDualDepthPeelingPass* pass, vtkAbstractVolumeMapper* mapper, vtkVolume* volume)
{
  std::string vs, gs, fs = "//VTK::DepthPeeling::Dec\n//VTK::CallWorker::Impl\n";
  if (!pass->PreReplaceShaderValues(vs, gs, fs, mapper, volume))
    return 0;
  if (fs.find("lastFrontColorTex") != std::string::npos)
    return cao::layout::CAO_PEEL_LAYER;
  if (fs.find("depthRangeTex") != std::string::npos)
    return cao::layout::CAO_PEEL_REMAINDER;
  if (fs.find("outerDepthTex") != std::string::npos)
    return cao::layout::CAO_PEEL_OUTSIDE;
  return 0;
}
}

bool QueryDepthPeeling(vtkRenderer* renderer, vtkVolume* volume, vtkAbstractVolumeMapper* mapper,
  PeelState& state, std::string& error)
{
  state = PeelState();
  vtkDualDepthPeelingPass* pass = PeelingPass(volume);
  if (!pass)
    return true;
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(renderer->GetRenderWindow());
  state.stage = Stage(pass, mapper, volume);
  if (!window || !state.stage)
  {
    error = "the depth-peeling pass's stage is not one a volume is drawn in";
    return false;
  }
  vtkShaderProgram* probe =
    window->GetShaderCache()->ReadyShaderProgram(ProbeVS, ProbeFS, "");
  if (!probe)
  {
    error = "the depth-peeling probe program did not build";
    return false;
  }
  const GLuint program = static_cast<GLuint>(probe->GetHandle());
  // Every sampler starts at a unit the pass would not use; what it sets, it names.
  GLint maxUnits = 0;
  glGetIntegerv(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, &maxUnits);
  const GLint unset = maxUnits - 1;
  GLint units[5];
  for (int i = 0; i < 5; ++i)
  {
    probe->SetUniformi(Samplers[i], unset);
    units[i] = unset;
  }
  pass->SetShaderParameters(probe, mapper, volume, nullptr);
  for (int i = 0; i < 5; ++i)
  {
    const GLint location = glGetUniformLocation(program, Samplers[i]);
    if (location >= 0)
      glGetUniformiv(program, location, &units[i]);
  }
  // Read the names bound on those units (the pass activated its textures).
  vtkOpenGLState* gl = window->GetState();
  GLint active = GL_TEXTURE0;
  glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
  auto name = [&](GLint unit) -> unsigned int {
    if (unit < 0 || unit >= unset)
      return 0;
    GLint bound = 0;
    gl->vtkglActiveTexture(GL_TEXTURE0 + unit);
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &bound);
    return static_cast<unsigned int>(bound);
  };
  if (state.stage == cao::layout::CAO_PEEL_REMAINDER)
    state.outer = name(units[4]);
  else
  {
    state.outer = name(units[0]);
    state.inner = name(units[1]);
    if (state.stage == cao::layout::CAO_PEEL_LAYER)
    {
      state.front = name(units[2]);
      state.opaque = name(units[3]);
    }
  }
  gl->vtkglActiveTexture(static_cast<unsigned int>(active));
  const bool complete = state.outer &&
    (state.stage == cao::layout::CAO_PEEL_REMAINDER || state.inner) &&
    (state.stage != cao::layout::CAO_PEEL_LAYER || (state.front && state.opaque));
  if (!complete)
    error = "the depth-peeling pass's textures were not found on the units it names";
  return complete;
}
}
