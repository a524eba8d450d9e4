// caoPixelCamera.h - a camera as the pixels of a frame see it, shared by
// every kind's G-buffer (surfaces, lines) and the grids planned from it.
#ifndef caoPixelCamera_h
#define caoPixelCamera_h

#include <string>

namespace cao
{

/// A camera as the pixels see it: the inverse of the composite
/// world-to-NDC matrix (row-major 4x4, NDC in [-1, 1]^3 as OpenGL's and
/// VTK's), and the image size. Pixel (i, j) is the ray through NDC
/// ((i + 1/2) / width * 2 - 1, (j + 1/2) / height * 2 - 1), row 0 at the
/// bottom as VTK's images.
struct PixelCamera
{
  double ndcToWorld[16];
  int width = 0, height = 0;
  static constexpr int MaximumSide = 16384;
};

/// Empty when `camera` is usable, else why not (with the limit).
std::string CheckPixelCamera(const PixelCamera& camera);
/// NDC (x, y, z) to world through the camera's inverse matrix; false when
/// the result is not finite.
bool NDCToWorld(const PixelCamera& camera, double x, double y, double z, double out[3]);
/// Pixel (i, j)'s ray: from its point on the near plane (`origin`), unit
/// `direction`, `length` to the far plane; false when degenerate or not
/// finite.
bool PixelRay(const PixelCamera& camera, int i, int j, double origin[3], double direction[3],
  double& length);
/// The inverse of camera.ndcToWorld (world to clip coordinates, before the
/// division); false when singular or not finite.
bool WorldToNDC(const PixelCamera& camera, double out[16]);

}

#endif
