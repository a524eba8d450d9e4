#include "caoSurfaceReference.h"

#include "caoParallelFor.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <thread>

namespace cao
{
namespace
{
constexpr double Pi = 3.14159265358979323846;

std::uint64_t SplitMix(std::uint64_t& state)
{
  std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

double Unit(std::uint64_t bits)
{
  return static_cast<double>(bits >> 11) * (1.0 / 9007199254740992.0); // [0, 1)
}

double RadicalInverse2(std::uint32_t i)
{
  i = (i << 16) | (i >> 16);
  i = ((i & 0x00ff00ffu) << 8) | ((i & 0xff00ff00u) >> 8);
  i = ((i & 0x0f0f0f0fu) << 4) | ((i & 0xf0f0f0f0u) >> 4);
  i = ((i & 0x33333333u) << 2) | ((i & 0xccccccccu) >> 2);
  i = ((i & 0x55555555u) << 1) | ((i & 0xaaaaaaaau) >> 1);
  return static_cast<double>(i) * (1.0 / 4294967296.0);
}

}

std::string SurfaceReferenceSettings::Validate() const
{
  if (this->rays < 1 || this->rays > MaximumRays)
    return "rays must be 1.." + std::to_string(MaximumRays) + " (got " + std::to_string(this->rays) + ")";
  if (!(this->radius > 0.0))
    return "the radius must be positive (infinity: unlimited); got " + std::to_string(this->radius);
  if (this->threads < 0 || this->threads > 1024)
    return "threads must be 0 (the hardware's) .. 1024";
  if (static_cast<int>(this->falloff) < 0 || static_cast<int>(this->falloff) > 2)
    return "unknown falloff";
  if (static_cast<int>(this->weighting) < 0 || static_cast<int>(this->weighting) > 1)
    return "unknown weighting";
  return std::string();
}

const char* FalloffName(AOFalloff falloff)
{
  switch (falloff)
  {
    case AOFalloff::Step:
      return "step";
    case AOFalloff::Linear:
      return "linear";
    case AOFalloff::Quartic:
      return "quartic";
  }
  return "?";
}

const char* WeightingName(AOWeighting weighting)
{
  return weighting == AOWeighting::Cosine ? "cosine" : "uniform";
}

bool ParseFalloff(const std::string& text, AOFalloff& falloff)
{
  for (AOFalloff f : { AOFalloff::Step, AOFalloff::Linear, AOFalloff::Quartic })
    if (text == FalloffName(f))
    {
      falloff = f;
      return true;
    }
  return false;
}

bool ParseWeighting(const std::string& text, AOWeighting& weighting)
{
  for (AOWeighting w : { AOWeighting::Cosine, AOWeighting::Uniform })
    if (text == WeightingName(w))
    {
      weighting = w;
      return true;
    }
  return false;
}

double FalloffValue(AOFalloff falloff, double distance, double radius)
{
  if (!(distance < radius))
    return 1.0;
  const double x = distance / radius;
  switch (falloff)
  {
    case AOFalloff::Step:
      return 0.0;
    case AOFalloff::Linear:
      return x;
    case AOFalloff::Quartic:
      return (x * x) * (x * x);
  }
  return 0.0;
}

double SelfDistance(const TriangleBVH& scene)
{
  const std::array<double, 6>& b = scene.Bounds();
  double d2 = 0.0;
  for (int d = 0; d < 3; ++d)
    if (b[2 * d + 1] > b[2 * d])
      d2 += (b[2 * d + 1] - b[2 * d]) * (b[2 * d + 1] - b[2 * d]);
  return std::max(1e-300, 1e-9 * std::sqrt(d2));
}

bool SurfaceReferenceAO(const TriangleBVH& scene, const double* points, const double* normals,
  std::size_t count, const SurfaceReferenceSettings& settings, double selfDistance, double* ao,
  std::string& error)
{
  error = settings.Validate();
  if (!error.empty())
    return false;
  if (!(selfDistance >= 0.0) || !std::isfinite(selfDistance))
  {
    error = "the self distance must be finite and not negative";
    return false;
  }
  for (std::size_t i = 0; i < count; ++i)
  {
    const double* n = normals + 3 * i;
    const double l2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    if (!(std::fabs(l2 - 1.0) < 1e-6) || !std::isfinite(points[3 * i]) ||
      !std::isfinite(points[3 * i + 1]) || !std::isfinite(points[3 * i + 2]))
    {
      error = "point " + std::to_string(i) + " has a non-finite position or a normal that is not unit length";
      return false;
    }
  }
  const int rays = settings.rays;
  const bool cosine = settings.weighting == AOWeighting::Cosine;
  const bool step = settings.falloff == AOFalloff::Step;
  ParallelFor(count, settings.threads, [&](std::size_t i) {
    const double* p = points + 3 * i;
    const double* n = normals + 3 * i;
    std::uint64_t state = settings.seed * 0x2545f4914f6cdd1dull + static_cast<std::uint64_t>(i);
    SplitMix(state);
    const double shift1 = Unit(SplitMix(state)), shift2 = Unit(SplitMix(state));
    // An orthonormal frame around n (Duff et al. 2017).
    const double sign = std::copysign(1.0, n[2]);
    const double a = -1.0 / (sign + n[2]);
    const double b = n[0] * n[1] * a;
    const double t[3] = { 1.0 + sign * n[0] * n[0] * a, sign * b, -sign * n[0] };
    const double s[3] = { b, sign + n[1] * n[1] * a, -n[1] };
    double sum = 0.0;
    for (int k = 0; k < rays; ++k)
    {
      double u1 = (k + 0.5) / rays + shift1;
      u1 -= std::floor(u1);
      double u2 = RadicalInverse2(static_cast<std::uint32_t>(k)) + shift2;
      u2 -= std::floor(u2);
      double x, y, z;
      const double phi = 2.0 * Pi * u2;
      if (cosine)
      {
        const double r = std::sqrt(u1);
        x = r * std::cos(phi);
        y = r * std::sin(phi);
        z = std::sqrt(std::max(0.0, 1.0 - u1));
      }
      else
      {
        z = u1;
        const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
        x = r * std::cos(phi);
        y = r * std::sin(phi);
      }
      const double d[3] = { x * t[0] + y * s[0] + z * n[0], x * t[1] + y * s[1] + z * n[1],
        x * t[2] + y * s[2] + z * n[2] };
      if (step)
      {
        sum += scene.Occluded(p, d, selfDistance, settings.radius) ? 0.0 : 1.0;
      }
      else
      {
        RayHit hit;
        const double distance = scene.Intersect(p, d, selfDistance, settings.radius, hit)
          ? hit.t
          : std::numeric_limits<double>::infinity();
        sum += FalloffValue(settings.falloff, distance, settings.radius);
      }
    }
    ao[i] = sum / rays;
  });
  return true;
}

namespace
{
/// A frame of `camera`'s size with nothing covered yet.
void ResetFrame(const PixelCamera& camera, double depthFill, SurfaceFrame& frame)
{
  // Assigned in place: a frame made again each camera change keeps its
  // memory (first touches of fresh pages cost more than the cast on some
  // machines: 160 MB took 0.54 s here).
  const std::size_t pixels = static_cast<std::size_t>(camera.width) * camera.height;
  frame.covered = 0;
  frame.width = camera.width;
  frame.height = camera.height;
  frame.triangle.assign(pixels, -1);
  frame.position.assign(3 * pixels, 0.0);
  frame.normal.assign(3 * pixels, 0.0);
  frame.depth.assign(pixels, depthFill);
  frame.ao.assign(pixels, std::numeric_limits<double>::quiet_NaN());
  frame.facing.assign(pixels, 0.0);
}

}

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

bool CastPrimary(const TriangleBVH& scene, const PixelCamera& camera, SurfaceFrame& frame,
  std::string& error)
{
  error = CheckPixelCamera(camera);
  if (!error.empty())
    return false;
  const std::size_t pixels = static_cast<std::size_t>(camera.width) * camera.height;
  ResetFrame(camera, std::numeric_limits<double>::infinity(), frame);
  auto unproject = [&camera](double x, double y, double z, double out[3]) {
    return NDCToWorld(camera, x, y, z, out);
  };
  ParallelFor(pixels, 0, [&](std::size_t index) {
    const int i = static_cast<int>(index % camera.width), j = static_cast<int>(index / camera.width);
    const double x = (i + 0.5) / camera.width * 2.0 - 1.0, y = (j + 0.5) / camera.height * 2.0 - 1.0;
    double nearPoint[3], farPoint[3], d[3];
    unproject(x, y, -1.0, nearPoint);
    unproject(x, y, 1.0, farPoint);
    for (int k = 0; k < 3; ++k)
      d[k] = farPoint[k] - nearPoint[k];
    const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (!(length > 0.0) || !std::isfinite(length))
      return;
    for (double& c : d)
      c /= length;
    RayHit hit;
    if (!scene.Intersect(nearPoint, d, 0.0, length, hit))
      return;
    std::array<double, 3> n = scene.Normal(hit.triangle);
    double c = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
    if (c > 0.0)
    {
      n = { { -n[0], -n[1], -n[2] } };
      c = -c;
    }
    frame.triangle[index] = hit.triangle;
    frame.depth[index] = hit.t;
    frame.facing[index] = -c;
    for (int k = 0; k < 3; ++k)
    {
      frame.position[3 * index + k] = nearPoint[k] + hit.t * d[k];
      frame.normal[3 * index + k] = n[k];
    }
  });
  frame.covered = std::count_if(frame.triangle.begin(), frame.triangle.end(),
    [](std::int64_t t) { return t >= 0; });
  return true;
}

bool ReferenceFrame(const TriangleBVH& scene, const SurfaceReferenceSettings& settings,
  SurfaceFrame& frame, std::string& error)
{
  std::vector<std::size_t> where;
  std::vector<double> points, normals;
  for (std::size_t i = 0; i < frame.triangle.size(); ++i)
    if (frame.triangle[i] >= 0)
    {
      where.push_back(i);
      points.insert(points.end(), &frame.position[3 * i], &frame.position[3 * i] + 3);
      normals.insert(normals.end(), &frame.normal[3 * i], &frame.normal[3 * i] + 3);
    }
  std::vector<double> ao(where.size());
  if (!SurfaceReferenceAO(scene, points.data(), normals.data(), where.size(), settings,
        SelfDistance(scene), ao.data(), error))
    return false;
  for (std::size_t k = 0; k < where.size(); ++k)
    frame.ao[where[k]] = ao[k];
  return true;
}


namespace
{
/// |2 p1 - p2 - p0|^2 of points p0, p1, p2 (x y z each) in `position`: how
/// far p0 is from the line through p1 and p2 continued (0 on a plane's
/// evenly spaced samples).
double Bend(const std::vector<double>& position, std::size_t p0, std::size_t p1, std::size_t p2)
{
  double s = 0.0;
  for (int d = 0; d < 3; ++d)
  {
    const double t = 2.0 * position[3 * p1 + d] - position[3 * p2 + d] - position[3 * p0 + d];
    s += t * t;
  }
  return s;
}
}

bool FrameFromDepth(const PixelCamera& camera, const std::vector<float>& depth, SurfaceFrame& frame,
  std::string& error)
{
  error = CheckPixelCamera(camera);
  if (!error.empty())
    return false;
  const int w = camera.width, h = camera.height;
  const std::size_t count = static_cast<std::size_t>(w) * h;
  if (depth.size() != count)
  {
    error = "the depth buffer does not match the image size";
    return false;
  }
  auto unproject = [&camera](double x, double y, double z, double out[3]) {
    return NDCToWorld(camera, x, y, z, out);
  };
  ResetFrame(camera, std::numeric_limits<double>::quiet_NaN(), frame);
  std::vector<char> valid(count, 0);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
    {
      const std::size_t k = static_cast<std::size_t>(j) * w + i;
      const double d = depth[k];
      if (!(d >= 0.0 && d < 1.0))
        continue;
      const double x = (i + 0.5) / w * 2.0 - 1.0, y = (j + 0.5) / h * 2.0 - 1.0;
      valid[k] = unproject(x, y, 2.0 * d - 1.0, &frame.position[3 * k]);
    }
  auto distance2 = [&frame](std::size_t a, std::size_t b) {
    double s = 0.0;
    for (int d = 0; d < 3; ++d)
    {
      const double t = frame.position[3 * a + d] - frame.position[3 * b + d];
      s += t * t;
    }
    return s;
  };
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
    {
      const std::size_t k = static_cast<std::size_t>(j) * w + i;
      if (!valid[k])
        continue;
      // Per axis the neighbour nearer in world space (the same surface at a step).
      double tangent[2][3];
      bool ok = true;
      for (int axis = 0; axis < 2 && ok; ++axis)
      {
        const std::size_t step = axis == 0 ? 1 : static_cast<std::size_t>(w);
        const bool hasMinus = axis == 0 ? i > 0 : j > 0;
        const bool hasPlus = axis == 0 ? i + 1 < w : j + 1 < h;
        const bool minus = hasMinus && valid[k - step], plus = hasPlus && valid[k + step];
        if (!minus && !plus)
        {
          ok = false;
          break;
        }
        // With two pixels on each side: the side that continues the pixel's
        // own plane (the smaller second difference |2 p1 - p2 - p0|), which
        // keeps a crease's pixels on their own face; else the nearer one.
        // (Measured: RMSE 0.0641 -> 0.0606 for VCT Medium at 256^2 on the
        // four shared meshes; the central difference where both sides are
        // smooth gave 0.0612.)
        const bool minus2 = minus && (axis == 0 ? i > 1 : j > 1) && valid[k - 2 * step];
        const bool plus2 = plus && (axis == 0 ? i + 2 < w : j + 2 < h) && valid[k + 2 * step];
        bool usePlus = plus && (!minus || distance2(k, k + step) <= distance2(k, k - step));
        if (minus2 && plus2)
          usePlus = Bend(frame.position, k, k + step, k + 2 * step) <= Bend(frame.position, k, k - step, k - 2 * step);
        const std::size_t a = usePlus ? k + step : k, b = usePlus ? k : k - step;
        for (int d = 0; d < 3; ++d)
          tangent[axis][d] = frame.position[3 * a + d] - frame.position[3 * b + d];
      }
      if (!ok)
        continue;
      double n[3] = { tangent[0][1] * tangent[1][2] - tangent[0][2] * tangent[1][1],
        tangent[0][2] * tangent[1][0] - tangent[0][0] * tangent[1][2],
        tangent[0][0] * tangent[1][1] - tangent[0][1] * tangent[1][0] };
      const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      if (!(length > 0.0) || !std::isfinite(length))
        continue;
      // The pixel's ray, near plane to far plane.
      const double x = (i + 0.5) / w * 2.0 - 1.0, y = (j + 0.5) / h * 2.0 - 1.0;
      double nearPoint[3], farPoint[3];
      if (!unproject(x, y, -1.0, nearPoint) || !unproject(x, y, 1.0, farPoint))
        continue;
      double ray[3] = { farPoint[0] - nearPoint[0], farPoint[1] - nearPoint[1], farPoint[2] - nearPoint[2] };
      const double rayLength = std::sqrt(ray[0] * ray[0] + ray[1] * ray[1] + ray[2] * ray[2]);
      double cosine = 0.0;
      for (int d = 0; d < 3; ++d)
      {
        n[d] /= length;
        ray[d] /= rayLength;
        cosine += n[d] * ray[d];
      }
      const double sign = cosine > 0.0 ? -1.0 : 1.0; // facing the camera
      double along = 0.0;
      for (int d = 0; d < 3; ++d)
      {
        frame.normal[3 * k + d] = sign * n[d];
        along += (frame.position[3 * k + d] - nearPoint[d]) * ray[d];
      }
      frame.facing[k] = std::fabs(cosine);
      frame.depth[k] = along;
      frame.triangle[k] = 0;
      ++frame.covered;
    }
  return true;
}

double Ripple(const std::vector<std::array<std::int64_t, 2>>& triples, const std::vector<double>& a,
  const std::vector<double>* b)
{
  double sum = 0;
  std::int64_t n = 0;
  for (const auto& t : triples)
  {
    const std::size_t p = static_cast<std::size_t>(t[0]), s = static_cast<std::size_t>(t[1]);
    const double da = a[p - s] - 2 * a[p] + a[p + s];
    const double db = b ? (*b)[p - s] - 2 * (*b)[p] + (*b)[p + s] : da;
    if (std::isfinite(da) && std::isfinite(db))
    {
      sum += da * db;
      ++n;
    }
  }
  return n ? std::sqrt(std::max(0.0, sum / n)) : 0;
}
}
