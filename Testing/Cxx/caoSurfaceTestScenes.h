// Scenes and cameras shared by the surface tests (kernel and GL): triangle
// quads and boxes, and a perspective camera as the pixels see it.
#ifndef caoSurfaceTestScenes_h
#define caoSurfaceTestScenes_h

#include "caoSurfaceReference.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <vector>

namespace caotest
{
struct TriangleScene
{
  std::vector<double> points;
  std::vector<std::int64_t> tris;
  /// Two triangles over four corners (x, y, z each, in order).
  void Quad(std::initializer_list<double> corners)
  {
    const std::int64_t base = static_cast<std::int64_t>(this->points.size() / 3);
    this->points.insert(this->points.end(), corners);
    this->tris.insert(this->tris.end(), { base, base + 1, base + 2, base, base + 2, base + 3 });
  }
  /// An axis-aligned box (closed).
  void Box(double x0, double x1, double y0, double y1, double z0, double z1)
  {
    this->Quad({ x0, y0, z1, x1, y0, z1, x1, y1, z1, x0, y1, z1 });
    this->Quad({ x0, y0, z0, x0, y1, z0, x1, y1, z0, x1, y0, z0 });
    this->Quad({ x0, y0, z0, x1, y0, z0, x1, y0, z1, x0, y0, z1 });
    this->Quad({ x0, y1, z0, x0, y1, z1, x1, y1, z1, x1, y1, z0 });
    this->Quad({ x0, y0, z0, x0, y0, z1, x0, y1, z1, x0, y1, z0 });
    this->Quad({ x1, y0, z0, x1, y1, z0, x1, y1, z1, x1, y0, z1 });
  }
};

/// The exact occlusion of cone `c` of `plan` by its rays (occupancy
/// "rays") at a point with normal +z beside the solid half-space x > a:
/// ConeTraceAO's frames for n = +z; a ray apex + tau r, sampled at tau = t0
/// + (m + 1/2) step up to t1 - step / 2 (steps of at most `rayStep`),
/// meets x > a if and only if (t1 - step / 2) r_x > a; the cosine-weighted
/// share of the rays that do.
template <class Plan>
double HalfSpaceRayOcclusion(const Plan& plan, std::size_t c, double a, double rayStep)
{
  const double dx = plan.cones[c][0], dy = plan.cones[c][1], dz = plan.cones[c][2];
  const double cs = dz >= 0.0 ? 1.0 : -1.0, ca = -1.0 / (cs + dz);
  const double u[3] = { 1.0 + cs * dx * dx * ca, cs * dx * dy * ca, -cs * dx };
  const double v[3] = { dx * dy * ca, cs + dy * dy * ca, -dy };
  const double t0 = plan.spheres.front().t - plan.spheres.front().r;
  const double t1 = plan.spheres.back().t + plan.spheres.back().r;
  double in = 0.0, all = 0.0;
  for (const auto& d : plan.disk)
  {
    double r[3];
    for (int k = 0; k < 3; ++k)
      r[k] = plan.cones[c][k] + plan.coneTangent * (d[0] * u[k] + d[1] * v[k]);
    const double length = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    const int steps = std::max(1, static_cast<int>(std::ceil((t1 - t0) * length / rayStep)));
    const double w = r[2] / length;
    all += w;
    in += (t1 - 0.5 * (t1 - t0) / steps) * r[0] > a ? w : 0.0;
  }
  return in / all;
}

/// ndcToWorld of a perspective camera at `eye` looking at `at` (up +z),
/// vertical view angle `fov` degrees, near and far planes, w x h pixels.
inline cao::PixelCamera LookAt(int w, int h, const double eye[3], const double at[3], double fov, double n,
  double f)
{
  double b[3] = { eye[0] - at[0], eye[1] - at[1], eye[2] - at[2] }; // backward
  double l = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
  for (double& v : b)
    v /= l;
  double r[3] = { -b[1], b[0], 0 }; // up (0, 0, 1) x backward
  l = std::sqrt(r[0] * r[0] + r[1] * r[1]);
  r[0] /= l;
  r[1] /= l;
  const double u[3] = { b[1] * r[2] - b[2] * r[1], b[2] * r[0] - b[0] * r[2], b[0] * r[1] - b[1] * r[0] };
  const double sy = 1.0 / std::tan(fov * 3.14159265358979323846 / 360.0), sx = sy * h / w;
  const double A = -(f + n) / (f - n), B = -2.0 * f * n / (f - n);
  // Inverse projection: eye coordinates (x/sx, y/sy, -1, (z - A)/B) up to w.
  const double pinv[16] = { 1 / sx, 0, 0, 0, 0, 1 / sy, 0, 0, 0, 0, 0, -1, 0, 0, 1 / B, A / B };
  const double view[16] = { r[0], u[0], b[0], eye[0], r[1], u[1], b[1], eye[1], r[2], u[2], b[2], eye[2], 0, 0, 0, 1 };
  cao::PixelCamera c;
  c.width = w;
  c.height = h;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
    {
      double s = 0;
      for (int k = 0; k < 4; ++k)
        s += view[4 * i + k] * pinv[4 * k + j];
      c.ndcToWorld[4 * i + j] = s;
    }
  return c;
}
}

#endif
