#include "caoAORadius.h"
#include "caoVectorMath.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace cao
{
double MeshArea(const MeshView& mesh)
{
  if (!mesh.points || !mesh.triangles)
    return 0.0;
  const std::vector<double>& p = *mesh.points;
  const std::vector<std::int64_t>& t = *mesh.triangles;
  const std::int64_t points = static_cast<std::int64_t>(p.size() / 3);
  double sum = 0.0;
  for (std::size_t k = 0; k + 2 < t.size(); k += 3)
  {
    const std::int64_t a = t[k], b = t[k + 1], c = t[k + 2];
    if (a < 0 || b < 0 || c < 0 || a >= points || b >= points || c >= points)
      continue;
    const Vec3 pa = LoadVec3(&p[3 * a]);
    const double area = 0.5 * glm::length(glm::cross(LoadVec3(&p[3 * b]) - pa, LoadVec3(&p[3 * c]) - pa));
    if (std::isfinite(area))
      sum += area;
  }
  return sum;
}

double DefaultAORadius(const std::array<double, 6>& b, double area)
{
  double volume = 1.0, diagonal2 = 0.0;
  for (int d = 0; d < 3; ++d)
  {
    const double e = b[2 * d + 1] - b[2 * d];
    if (!(e >= 0.0) || !std::isfinite(e))
      return 0.0;
    volume *= e;
    diagonal2 += e * e;
  }
  const double diagonal = std::sqrt(diagonal2);
  if (!(diagonal > 0.0) || !std::isfinite(diagonal))
    return 0.0;
  const double most = DefaultAORadiusMost * diagonal, least = DefaultAORadiusLeast * diagonal;
  if (!(area > 0.0) || !std::isfinite(area) || !std::isfinite(volume))
    return most;
  return std::clamp(2.0 * volume / area, least, most);
}

std::string CheckAORadius(double radius, double diagonal)
{
  if (!(diagonal > 0.0) || !std::isfinite(diagonal))
    return std::string();
  if (radius >= AORadiusLeast * diagonal && radius <= AORadiusMost * diagonal)
    return std::string();
  char text[320];
  std::snprintf(text, sizeof(text),
    "the AO radius %g is outside %g to %g (1e-6 to 1e3 times the scene's bounding-box diagonal, %g)", radius,
    AORadiusLeast * diagonal, AORadiusMost * diagonal, diagonal);
  return text;
}

std::string ScreenSpaceUnresolvedRadius(double radius, double pixel, const std::string& label)
{
  if (!(pixel > 0.0) || !std::isfinite(pixel) || !(radius < pixel))
    return std::string();
  std::ostringstream o;
  o << "the AO radius " << radius << " is under a pixel at the scene's centre (about " << pixel << "): " << label
    << " reads the screen's pixels and sees no neighbour within it, so it gives almost no AO; raise the "
       "radius, the image size or the zoom";
  return o.str();
}
}
