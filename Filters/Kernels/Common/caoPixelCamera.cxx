#include "caoPixelCamera.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace cao
{

std::string CheckPixelCamera(const PixelCamera& camera)
{
  if (camera.width < 1 || camera.height < 1 || camera.width > PixelCamera::MaximumSide ||
    camera.height > PixelCamera::MaximumSide)
    return "the image must be 1.." + std::to_string(PixelCamera::MaximumSide) + " pixels a side (got " +
      std::to_string(camera.width) + "x" + std::to_string(camera.height) + ")";
  for (double m : camera.ndcToWorld)
    if (!std::isfinite(m))
      return "the camera's matrix is not finite";
  return std::string();
}


bool WorldToNDC(const PixelCamera& camera, double out[16])
{
  // Gauss-Jordan with partial pivoting on [M | I].
  const double* m = camera.ndcToWorld;
  double a[4][8];
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 8; ++c)
      a[r][c] = c < 4 ? m[4 * r + c] : (c - 4 == r ? 1.0 : 0.0);
  for (int c = 0; c < 4; ++c)
  {
    int pivot = c;
    for (int r = c + 1; r < 4; ++r)
      if (std::fabs(a[r][c]) > std::fabs(a[pivot][c]))
        pivot = r;
    if (!(std::fabs(a[pivot][c]) > 0.0) || !std::isfinite(a[pivot][c]))
      return false;
    std::swap(a[c], a[pivot]);
    const double inv = 1.0 / a[c][c];
    for (double& v : a[c])
      v *= inv;
    for (int r = 0; r < 4; ++r)
      if (r != c)
      {
        const double f = a[r][c];
        for (int k = 0; k < 8; ++k)
          a[r][k] -= f * a[c][k];
      }
  }
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      out[4 * r + c] = a[r][c + 4];
  for (int k = 0; k < 16; ++k)
    if (!std::isfinite(out[k]))
      return false;
  return true;
}

bool NDCToWorld(const PixelCamera& camera, double x, double y, double z, double out[3])
{
  const double* m = camera.ndcToWorld;
  const double w = m[12] * x + m[13] * y + m[14] * z + m[15];
  for (int r = 0; r < 3; ++r)
    out[r] = (m[4 * r] * x + m[4 * r + 1] * y + m[4 * r + 2] * z + m[4 * r + 3]) / w;
  return std::isfinite(out[0]) && std::isfinite(out[1]) && std::isfinite(out[2]);
}

bool PixelRay(const PixelCamera& camera, int i, int j, double origin[3], double direction[3],
  double& length)
{
  const double x = (i + 0.5) / camera.width * 2.0 - 1.0, y = (j + 0.5) / camera.height * 2.0 - 1.0;
  double farPoint[3];
  if (!NDCToWorld(camera, x, y, -1.0, origin) || !NDCToWorld(camera, x, y, 1.0, farPoint))
    return false;
  for (int k = 0; k < 3; ++k)
    direction[k] = farPoint[k] - origin[k];
  length = std::sqrt(direction[0] * direction[0] + direction[1] * direction[1] + direction[2] * direction[2]);
  if (!(length > 0.0) || !std::isfinite(length))
    return false;
  for (int k = 0; k < 3; ++k)
    direction[k] /= length;
  return true;
}

}
