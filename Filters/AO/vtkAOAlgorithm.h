/**
 * @class   vtkAOAlgorithm
 * @brief   What the three ambient-occlusion filters share: where they run.
 *
 * vtkLocalAmbientOcclusion, vtkClipDepthMaps and
 * vtkContextualAmbientOcclusion derive from it, so the backend, the render
 * window and the thread count are declared, documented and checked once.
 *
 * Backend: CPU, OPENGL (compute shaders in a headless EGL or OSMesa OpenGL
 * >= 4.3 context; an error when there is none) or AUTO (the default):
 * OpenGL on a hardware GPU; the CPU on a software rasteriser (Mesa's
 * llvmpipe runs these shaders slower than the CPU kernels), with one warning
 * when there is no OpenGL 4.3 at all, and whenever the calling thread
 * already has an application's OpenGL context current (ParaView's view, a
 * VTK window): Auto never brings in a second context there. The output's
 * field array "ComputeBackend" says what ran and on which context, and why
 * Auto chose the CPU. A headless context is current only during the
 * filter's GL calls: an application context current before is released
 * meanwhile and made current again.
 *
 * RenderWindow: a VTK OpenGL render window whose context the OpenGL backend
 * uses instead of a headless one. The filter makes it current when it
 * executes, uses the window's GLEW, and restores every OpenGL state it
 * changes. Call ReleaseGraphicsResources() before the window's context is
 * destroyed; if it is gone first, the filter forgets its objects without GL
 * calls.
 *
 * Settings are taken as given: a value outside its stated range is an error
 * of the next update (nothing is clamped).
 */
#ifndef vtkAOAlgorithm_h
#define vtkAOAlgorithm_h

#include "caoFiltersAOModule.h" // For export macro
#include "vtkCAOBackend.h" // For the Backend values
#include "vtkImageAlgorithm.h"

#include <memory> // For the GPU session

class vtkRenderWindow;
namespace vtkCAO
{
class GPUSession;
}

class CAOFILTERSAO_EXPORT vtkAOAlgorithm : public vtkImageAlgorithm
{
public:
  vtkTypeMacro(vtkAOAlgorithm, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Where the work runs (see the class documentation).
  enum Backends
  {
    AUTO = vtkCAO::BACKEND_AUTO,
    CPU = vtkCAO::BACKEND_CPU,
    OPENGL = vtkCAO::BACKEND_OPENGL
  };

  ///@{
  /// Backend (Backends). Default AUTO.
  vtkSetMacro(Backend, int);
  vtkGetMacro(Backend, int);
  void SetBackendToAuto() { this->SetBackend(AUTO); }
  void SetBackendToCPU() { this->SetBackend(CPU); }
  void SetBackendToOpenGL() { this->SetBackend(OPENGL); }
  ///@}

  ///@{
  /// The render window whose context the OpenGL backend uses; null (the
  /// default): a headless EGL or OSMesa context.
  virtual void SetRenderWindow(vtkRenderWindow* window);
  vtkGetObjectMacro(RenderWindow, vtkRenderWindow);
  ///@}

  ///@{
  /// Maximum number of threads; 0 (default) lets vtkSMPTools decide.
  vtkSetMacro(NumberOfThreads, int);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  /// Free the GPU objects and the OpenGL context this filter holds.
  virtual void ReleaseGraphicsResources();

protected:
  vtkAOAlgorithm();
  ~vtkAOAlgorithm() override;

  /// Whether Backend and NumberOfThreads are valid; an error if not.
  bool CheckExecutionSettings();
  /// Decide where this execution runs: true for OpenGL. `failed` after an
  /// error (OpenGL forced and unavailable).
  bool ResolveBackend(bool& failed);

  int Backend = AUTO;
  int NumberOfThreads = 0;
  vtkRenderWindow* RenderWindow = nullptr;
  std::unique_ptr<vtkCAO::GPUSession> GPU;

private:
  vtkAOAlgorithm(const vtkAOAlgorithm&) = delete;
  void operator=(const vtkAOAlgorithm&) = delete;
};

#endif
