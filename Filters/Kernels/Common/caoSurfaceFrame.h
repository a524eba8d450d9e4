// caoSurfaceFrame.h - a frame's G-buffer as every surface technique reads
// it: per pixel the first surface a camera sees (made by a ray cast or from
// a drawn depth: Surface/caoSurfaceReference.h), and the AO there. Shared
// by the techniques, the scene's frustum grid (caoSceneGrid.h) and the GL
// layer.
#ifndef caoSurfaceFrame_h
#define caoSurfaceFrame_h

#include <cstdint>
#include <vector>

namespace cao
{

/// What the camera sees: per pixel the first surface (the G-buffer every
/// method starts from), and the AO there.
struct SurfaceFrame
{
  int width = 0, height = 0;
  std::vector<std::int64_t> triangle; ///< -1: background
  std::vector<double> position;       ///< x, y, z per pixel
  std::vector<double> normal;         ///< facing the camera (two-sided)
  std::vector<double> depth;          ///< distance along the pixel's ray
  std::vector<double> ao;             ///< NaN on background
  std::vector<double> facing;         ///< |cos| between the normal and the ray
  std::int64_t covered = 0;
};

}

#endif
