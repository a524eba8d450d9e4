// caoLineTestScenes.h - what the line tests share (header-only, VTK-free):
// the depth buffer a renderer would draw for a line G-buffer.
#ifndef caoLineTestScenes_h
#define caoLineTestScenes_h

#include "caoCapsules.h"

#include <vector>

namespace caotest
{
/// The window depth (0..1; 1: background) a renderer would draw for
/// `frame`'s surface points under `camera`, `offset` nearer the camera;
/// empty when the camera does not invert.
inline std::vector<float> DrawnDepth(const cao::LineFrame& frame, const cao::PixelCamera& camera, double offset = 0.0)
{
  double toNDC[16];
  if (!cao::WorldToNDC(camera, toNDC))
    return std::vector<float>();
  std::vector<float> depth(frame.segment.size(), 1.0f);
  for (std::size_t k = 0; k < frame.segment.size(); ++k)
    if (frame.segment[k] >= 0)
    {
      const double* x = &frame.position[3 * k];
      double c[4];
      for (int row = 0; row < 4; ++row)
        c[row] = toNDC[4 * row] * x[0] + toNDC[4 * row + 1] * x[1] + toNDC[4 * row + 2] * x[2] + toNDC[4 * row + 3];
      depth[k] = static_cast<float>(0.5 * (c[2] / c[3]) + 0.5 - offset);
    }
  return depth;
}
}

#endif
