/**
 * vtkCAOBackend.h — where an AO computation runs: the one definition of
 * the Backend values every class with a Backend property uses (the filters
 * through vtkAOAlgorithm, the surface pass, the GPU session; ParaView's XML
 * lists the same numbers). Installed: the public headers that name them
 * include it.
 */
#ifndef vtkCAOBackend_h
#define vtkCAOBackend_h

namespace vtkCAO
{
/// The Backend property's values.
enum BackendChoice
{
  BACKEND_AUTO = 0,  ///< OpenGL 4.3 on a hardware GPU, else the CPU
  BACKEND_CPU = 1,   ///< the CPU kernels
  BACKEND_OPENGL = 2 ///< OpenGL 4.3, even a software rasteriser; none: an error
};
}

#endif
