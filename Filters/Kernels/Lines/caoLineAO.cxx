#include "caoLineAO.h"

#include "caoAOReference.h"
#include "caoParallelFor.h"
#include "caoVectorMath.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>

namespace cao
{
namespace
{
constexpr double Pi = 3.14159265358979323846;
constexpr int SampleSets = 16;
/// The mean area a unit cube projects along a random direction (Cauchy:
/// a quarter of its surface): a thin line's supercover per unit length.
constexpr double SupercoverArea = 1.5;

double Unit(std::mt19937_64& rng)
{
  return static_cast<double>(rng() >> 11) * (1.0 / 9007199254740992.0); // [0, 1)
}

/// A point of `grid` in voxel units: voxel (i, j, k) spans [i, i + 1) x
/// [j, j + 1) x [k, k + 1).
Vec3 ToVoxels(const BitGrid& grid, const double world[3])
{
  double g[3];
  grid.ToGrid(world, g);
  return { (g[0] - grid.origin[0]) / grid.voxel, (g[1] - grid.origin[1]) / grid.voxel,
    (g[2] - grid.origin[2]) / grid.voxel };
}

/// A direction in the grid's frame.
Vec3 ToGridDirection(const BitGrid& grid, const double world[3])
{
  double g[3];
  grid.ToGrid(world, g);
  return LoadVec3(g);
}

/// The parameter range of segment p0 + s (p1 - p0), s in [s0, s1], inside
/// the closed box [lo, hi]; false when it misses.
bool ClipToBox(const Vec3& p0, const Vec3& d, const Vec3& lo, const Vec3& hi, double& s0, double& s1)
{
  for (int a = 0; a < 3; ++a)
  {
    if (d[a] == 0.0)
    {
      if (p0[a] < lo[a] || p0[a] > hi[a])
        return false;
      continue;
    }
    double t0 = (lo[a] - p0[a]) / d[a], t1 = (hi[a] - p0[a]) / d[a];
    if (t0 > t1)
      std::swap(t0, t1);
    s0 = std::max(s0, t0);
    s1 = std::min(s1, t1);
    if (s0 > s1)
      return false;
  }
  return true;
}

/// The squared distance from q to segment [p0, p0 + d].
double SegmentDistance2(const Vec3& q, const Vec3& p0, const Vec3& d)
{
  const double dd = glm::dot(d, d);
  double s = dd > 0.0 ? glm::dot(q - p0, d) / dd : 0.0;
  s = std::min(1.0, std::max(0.0, s));
  const Vec3 e = q - (p0 + s * d);
  return glm::dot(e, e);
}

void SetBit(BitGrid& grid, int i, int j, int k)
{
  grid.bits[(static_cast<std::size_t>(j) * grid.nx + i) * grid.words + (k >> 5)] |= 1u << (k & 31);
}
}

std::string LineAOSettings::Validate() const
{
  if (this->weights == LineAOWeights::Paper && this->estimator != LineAOEstimator::Prisms)
    return "the paper's weights weigh the prisms: they need the prisms estimator (got rays)";
  if (!(this->radius > 0.0) || !std::isfinite(this->radius))
    return "the line AO radius must be finite and positive (got " + std::to_string(this->radius) + ")";
  if (!(this->tubeRadius >= 0.0) || !std::isfinite(this->tubeRadius))
    return "the tube radius must be finite and not negative (0: lines drawn as lines; got " +
      std::to_string(this->tubeRadius) + ")";
  if (this->samples < 1 || this->samples > MaximumSamples)
    return "line AO samples must be 1.." + std::to_string(MaximumSamples) + " (got " +
      std::to_string(this->samples) + ")";
  if (this->slices < 32 || this->slices > 1024 || this->slices % 32 != 0)
    return "depth slices must be 32..1024 and a multiple of 32 (got " + std::to_string(this->slices) + ")";
  if (!(this->strength >= 0.0 && this->strength <= 100.0))
    return "the line AO strength must be 0..100 (1: calibrated; got " + std::to_string(this->strength) + ")";
  if (!(this->aoFactor >= 0.0) || !std::isfinite(this->aoFactor))
    return "the AO factor must be finite and not negative";
  if (!(this->voxelOffset >= 0.0 && this->voxelOffset <= 2.0))
    return "the line voxels' offset along a ray must be 0..2 voxels (got " + std::to_string(this->voxelOffset) + ")";
  if (static_cast<int>(this->weights) < 0 || static_cast<int>(this->weights) > 1)
    return "unknown line AO weights";
  if (static_cast<int>(this->hemisphere) < 0 || static_cast<int>(this->hemisphere) > 1)
    return "unknown line AO hemisphere";
  if (this->threads < 0 || this->threads > 1024)
    return "threads must be 0 (the hardware's) .. 1024";
  return std::string();
}

const char* LineAOWeightsName(LineAOWeights weights)
{
  return weights == LineAOWeights::Paper ? "paper" : "normalized";
}

bool ParseLineAOWeights(const std::string& text, LineAOWeights& weights)
{
  for (LineAOWeights w : { LineAOWeights::Normalized, LineAOWeights::Paper })
    if (text == LineAOWeightsName(w))
    {
      weights = w;
      return true;
    }
  return false;
}

const char* LineAOEstimatorName(LineAOEstimator estimator)
{
  return estimator == LineAOEstimator::Prisms ? "prisms" : "rays";
}

bool ParseLineAOEstimator(const std::string& text, LineAOEstimator& estimator)
{
  for (LineAOEstimator e : { LineAOEstimator::Rays, LineAOEstimator::Prisms })
    if (text == LineAOEstimatorName(e))
    {
      estimator = e;
      return true;
    }
  return false;
}

const char* LineAOHemisphereName(LineAOHemisphere hemisphere)
{
  return hemisphere == LineAOHemisphere::CameraFacing ? "camera" : "normal";
}

bool ParseLineAOHemisphere(const std::string& text, LineAOHemisphere& hemisphere)
{
  for (LineAOHemisphere h : { LineAOHemisphere::Normal, LineAOHemisphere::CameraFacing })
    if (text == LineAOHemisphereName(h))
    {
      hemisphere = h;
      return true;
    }
  return false;
}

std::string LineSegments::Validate() const
{
  if (this->points.size() % 3 != 0)
    return "the line points are not x, y, z triples";
  if (this->segments.size() % 2 != 0)
    return "the segments are not pairs of point ids";
  const std::int64_t n = static_cast<std::int64_t>(this->points.size() / 3);
  // (Both scans on the CPU's threads; the first bad one found again in order.)
  std::atomic<bool> notFinite{ false }, outside{ false };
  ParallelForBlocks(this->points.size(), 0, [&](std::size_t first, std::size_t last) {
    for (std::size_t i = first; i < last; ++i)
      if (!std::isfinite(this->points[i]))
      {
        notFinite = true;
        return;
      }
  });
  if (notFinite)
    return "a line point has a NaN or infinite coordinate";
  ParallelForBlocks(this->segments.size(), 0, [&](std::size_t first, std::size_t last) {
    for (std::size_t i = first; i < last; ++i)
      if (this->segments[i] < 0 || this->segments[i] >= n)
      {
        outside = true;
        return;
      }
  });
  if (outside)
    for (std::int64_t id : this->segments)
      if (id < 0 || id >= n)
        return "a segment's point id " + std::to_string(id) + " is outside 0.." + std::to_string(n - 1);
  return std::string();
}

bool PlanLineGrid(const LineSegments& lines, const double right[3], const double up[3],
  const LineAOSettings& settings, BitGrid& grid, std::string& error, const std::array<double, 6>* also)
{
  error = settings.Validate();
  if (error.empty())
    error = lines.Validate();
  if (!error.empty())
    return false;
  std::array<double, 9> axes;
  if (!EyeAxes(right, up, axes, error))
    return false;
  BitGrid frame;
  frame.axes = axes;
  std::array<double, 6> b{ { 0, 0, 0, 0, 0, 0 } };
  bool any = false;
  // (Each block's bounds on the CPU's threads, then all of them.)
  std::vector<std::array<double, 6>> blockBounds(ParallelBlocks(lines.segments.size()));
  ParallelForBlocks(lines.segments.size(), 0, [&](std::size_t first, std::size_t last) {
    std::array<double, 6>& c = blockBounds[first / ParallelBlockSize];
    for (std::size_t i = first; i < last; ++i)
    {
      double g[3];
      frame.ToGrid(&lines.points[3 * static_cast<std::size_t>(lines.segments[i])], g);
      for (int d = 0; d < 3; ++d)
      {
        c[2 * d] = i > first ? std::min(c[2 * d], g[d]) : g[d];
        c[2 * d + 1] = i > first ? std::max(c[2 * d + 1], g[d]) : g[d];
      }
    }
  });
  for (const std::array<double, 6>& c : blockBounds)
  {
    for (int d = 0; d < 3; ++d)
    {
      b[2 * d] = any ? std::min(b[2 * d], c[2 * d]) : c[2 * d];
      b[2 * d + 1] = any ? std::max(b[2 * d + 1], c[2 * d + 1]) : c[2 * d + 1];
    }
    any = true;
  }
  if (!any)
  {
    error = "there are no line segments";
    return false;
  }
  if (also && (*also)[0] <= (*also)[1])
    for (int d = 0; d < 3; ++d)
    {
      b[2 * d] = std::min(b[2 * d], (*also)[2 * d]);
      b[2 * d + 1] = std::max(b[2 * d + 1], (*also)[2 * d + 1]);
    }
  if (!PlanGrid(b, settings.radius + settings.tubeRadius, settings.slices, grid, error))
    return false;
  grid.axes = axes;
  return true;
}

std::string CheckVoxelizeLines(const LineSegments& lines, double tubeRadius, const BitGrid& grid)
{
  std::string error = lines.Validate();
  if (!error.empty())
    return error;
  if (grid.IsFrustum() || grid.nx < 1 || grid.ny < 1 || grid.words < 1 || !(grid.voxel > 0.0))
    return "line voxelization needs a planned world or eye grid";
  if (!(tubeRadius >= 0.0) || !std::isfinite(tubeRadius))
    return "the tube radius must be finite and not negative";
  const double rho = tubeRadius / grid.voxel;
  const int dims[3] = { grid.nx, grid.ny, grid.slices };
  // The voxels the pieces' boxes visit, bounded before any is: a tube far
  // wider than the grid's voxels would otherwise visit the grid per piece.
  const double side = LinePieceLength + 2.0 * rho + 3.0;
  const double perPiece = std::min(side * side * side, static_cast<double>(dims[0]) * dims[1] * dims[2]);
  // (Each block of segments summed on the CPU's threads, then the blocks in order.)
  const std::size_t count = lines.segments.size() / 2;
  std::vector<double> blockVisits(ParallelBlocks(count), 0.0);
  ParallelForBlocks(count, 0, [&](std::size_t first, std::size_t last) {
    double sum = 0.0;
    for (std::size_t s = first; s < last; ++s)
    {
      const double* a = &lines.points[3 * static_cast<std::size_t>(lines.segments[2 * s])];
      const double* b = &lines.points[3 * static_cast<std::size_t>(lines.segments[2 * s + 1])];
      const double length = std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
        (a[2] - b[2]) * (a[2] - b[2])) / grid.voxel;
      sum += std::max(1.0, std::ceil(length / LinePieceLength)) * perPiece;
    }
    blockVisits[first / ParallelBlockSize] = sum;
  });
  double visits = 0.0;
  for (double v : blockVisits)
    visits += v;
  if (visits > MaximumVoxelVisits)
    return "voxelizing these lines would visit about " + std::to_string(static_cast<long long>(visits)) +
      " voxels (the tube radius " + std::to_string(tubeRadius) + " is " + std::to_string(rho) +
      " voxels of the grid); at most " + std::to_string(static_cast<long long>(MaximumVoxelVisits)) +
      ": use a smaller tube radius or fewer slices";
  return std::string();
}

std::string LineRadiusWithinTubes(double radius, double tubeRadius)
{
  if (!(tubeRadius > 0.0) || !(radius <= tubeRadius))
    return std::string();
  std::ostringstream o;
  o << "the AO radius " << radius << " is within the lines' tubes (radius " << tubeRadius
    << "): the half balls around a line hold only its own tube, so the lines get no AO; raise the "
       "radius above " << LineDefaultRadiusFloor(tubeRadius) << " or draw the lines thinner";
  return o.str();
}

bool VoxelizeLines(const LineSegments& lines, double tubeRadius, BitGrid& grid, std::string& error)
{
  error = CheckVoxelizeLines(lines, tubeRadius, grid);
  if (!error.empty())
    return false;
  const double rho = tubeRadius / grid.voxel, rho2 = rho * rho;
  const int dims[3] = { grid.nx, grid.ny, grid.slices };
  constexpr double PieceLength = LinePieceLength;
  grid.bits.assign(static_cast<std::size_t>(grid.nx) * grid.ny * grid.words, 0u);
  for (std::size_t s = 0; s + 1 < lines.segments.size(); s += 2)
  {
    const Vec3 a = ToVoxels(grid, &lines.points[3 * static_cast<std::size_t>(lines.segments[s])]);
    const Vec3 b = ToVoxels(grid, &lines.points[3 * static_cast<std::size_t>(lines.segments[s + 1])]);
    const Vec3 d = b - a;
    const int pieces = std::max(1, static_cast<int>(std::ceil(glm::length(d) / PieceLength)));
    for (int p = 0; p < pieces; ++p)
    {
      const Vec3 p0 = a + d * (static_cast<double>(p) / pieces);
      const Vec3 p1 = p + 1 == pieces ? b : a + d * (static_cast<double>(p + 1) / pieces);
      const Vec3 pd = p1 - p0;
      int lo[3], hi[3];
      bool empty = false;
      for (int c = 0; c < 3; ++c)
      {
        // In double, clamped to the grid before the cast (a tube far wider
        // than the grid would overflow an int).
        const double mn = std::min(p0[c], p1[c]) - rho, mx = std::max(p0[c], p1[c]) + rho;
        const double first = std::max(0.0, std::floor(mn) - 1.0), last = std::min(dims[c] - 1.0, std::floor(mx) + 1.0);
        if (!(first <= last))
        {
          empty = true;
          break;
        }
        lo[c] = static_cast<int>(first);
        hi[c] = static_cast<int>(last);
      }
      if (empty)
        continue;
      for (int k = lo[2]; k <= hi[2]; ++k)
        for (int j = lo[1]; j <= hi[1]; ++j)
          for (int i = lo[0]; i <= hi[0]; ++i)
          {
            double s0 = 0.0, s1 = 1.0;
            const Vec3 cell(i, j, k);
            bool set = ClipToBox(p0, pd, cell, cell + Vec3(1.0), s0, s1);
            if (!set && rho > 0.0)
              set = SegmentDistance2(cell + Vec3(0.5), p0, pd) <= rho2;
            if (set)
              SetBit(grid, i, j, k);
          }
    }
  }
  return true;
}

std::vector<double> LineAOSamples(int count, std::uint64_t seed)
{
  count = std::max(1, count);
  std::vector<double> out(static_cast<std::size_t>(SampleSets) * 2 * count);
  std::mt19937_64 rng(seed * 0x9e3779b97f4a7c15ull + 0x2545f4914f6cdd1dull);
  for (int set = 0; set < SampleSets; ++set)
  {
    double* xy = &out[static_cast<std::size_t>(set) * 2 * count];
    for (int n = 0; n < count; ++n)
    {
      // Mitchell's best candidate: of n + 1 uniform candidates in the disk,
      // the one farthest from the points placed so far.
      double best = -1.0, bx = 0.0, by = 0.0;
      for (int c = 0; c <= std::min(n, 32); ++c)
      {
        const double r = std::sqrt(Unit(rng)), phi = 2.0 * Pi * Unit(rng);
        const double x = r * std::cos(phi), y = r * std::sin(phi);
        double nearest = std::numeric_limits<double>::infinity();
        for (int m = 0; m < n; ++m)
          nearest = std::min(nearest,
            (x - xy[2 * m]) * (x - xy[2 * m]) + (y - xy[2 * m + 1]) * (y - xy[2 * m + 1]));
        if (nearest > best)
        {
          best = nearest;
          bx = x;
          by = y;
        }
      }
      xy[2 * n] = bx;
      xy[2 * n + 1] = by;
    }
  }
  return out;
}

LineHalfBall LineHalfBallAt(const BitGrid& grid, const LineAOSettings& settings, const double axisPoint[3],
  const double tangent[3], const double view[3], const double* surface, const double* normal)
{
  const double h = grid.voxel;
  const double rho = settings.tubeRadius / h;
  Vec3 T = ToGridDirection(grid, tangent);
  const bool line = glm::dot(T, T) > 0.0;
  if (line)
    T = glm::normalize(T);
  // The half ball: its centre, the normal w of its base plane, and the
  // plane's offset from the centre along w (voxel units).
  Vec3 centre, w;
  double base = 0.0;
  bool cosine = settings.hemisphere == LineAOHemisphere::Normal && surface && normal;
  if (cosine)
  {
    // At the tube's surface, facing its normal (the surface definition),
    // turned across the line: a pixel's segment is the one drawn nearest,
    // and where that is a neighbour of the segment under the pixel (short
    // segments, every pixel or two), the ray meets its end cap, whose
    // normal leans along the line, and a half ball leaning so holds the
    // own tube ahead of it (an isolated straight line of 200 segments drawn
    // as an 8-pixel tube: mean AO 0.91, down to 0.79; of 2 segments 0.999).
    // The own tube's voxel centres lie within max(rho, half a voxel
    // diagonal: a thin tube's supercover) of its axis, and the surface
    // point lies d from it (rho on the tube voxelized; less on a cap, or
    // where a tube drawn a fixed number of pixels wide is thinner in the
    // world than the one voxelized): the base plane goes max(rho, half
    // diagonal) - d past the point, so the own voxels never occlude it.
    centre = ToVoxels(grid, surface);
    w = Normalized(ToGridDirection(grid, normal));
    if (line)
      w -= glm::dot(w, T) * T;
    if (glm::length(w) > 0.1) // (else an end cap seen along the line: the paper's half ball)
    {
      w = glm::normalize(w);
      Vec3 radial = centre - ToVoxels(grid, axisPoint);
      if (line)
        radial -= glm::dot(radial, T) * T;
      base = std::max(0.0, std::max(rho, LineHalfVoxelDiagonal) - glm::length(radial));
    }
    else
      cosine = false;
  }
  if (!cosine)
  {
    // The seed's (Eq. 3.5-3.7): at the axis, toward the camera and
    // perpendicular to the line (a line along the view ray: any normal
    // perpendicular to it), moved off the axis past the own voxels.
    centre = ToVoxels(grid, axisPoint);
    const Vec3 toCamera = -Normalized(ToGridDirection(grid, view));
    w = line ? toCamera - glm::dot(toCamera, T) * T : toCamera;
    if (!(glm::length(w) > 1e-9))
      w = glm::cross(T, std::fabs(T.x) < 0.6 ? Vec3(1, 0, 0) : Vec3(0, 1, 0));
    w = glm::normalize(w);
    base = std::max(rho, LineHalfVoxelDiagonal);
  }
  LineHalfBall ball;
  StoreVec3(centre, ball.centre);
  StoreVec3(w, ball.w);
  StoreVec3(T, ball.tangent);
  ball.base = base + 1e-9;
  ball.line = line;
  ball.cosine = cosine;
  return ball;
}

LineHalfBall LineHalfBallOfPixel(const BitGrid& grid, const LineAOSettings& settings, const LineFrame& frame,
  std::size_t p)
{
  // A G-buffer of lines drawn as lines has no surface, and a pixel whose
  // normal is 0 (a flat line's in LineFrameFromDepth) neither: their half
  // balls face the camera.
  const std::size_t pixels = static_cast<std::size_t>(frame.width) * frame.height;
  const bool surfaces = frame.position.size() == 3 * pixels && frame.normal.size() == 3 * pixels;
  const double* n = surfaces ? &frame.normal[3 * p] : nullptr;
  const bool faced = n && (n[0] != 0.0 || n[1] != 0.0 || n[2] != 0.0);
  return LineHalfBallAt(grid, settings, &frame.axis[3 * p], &frame.tangent[3 * p], &frame.view[3 * p],
    faced ? &frame.position[3 * p] : nullptr, faced ? n : nullptr);
}

int LineSampleSet(int i, int j)
{
  return (i & 3) + 4 * (j & 3);
}

double LineOccupancyOf(const BitGrid& grid, const LineAOSettings& settings, const double* samples,
  const LineHalfBall& ball, const BitGrid* solids, double* solidOccupancy)
{
  const double h = grid.voxel;
  const double R = settings.radius / h;
  const Vec3 centre = LoadVec3(ball.centre), w = LoadVec3(ball.w), T = LoadVec3(ball.tangent);
  const double base = ball.base;
  const bool line = ball.line, cosine = ball.cosine;
  const bool paper = settings.weights == LineAOWeights::Paper;
  double sum = 0.0, solidSum = 0.0, weights = 0.0;
  for (int n = 0; n < settings.samples; ++n)
  {
    // The prism runs along the view axis through the voxel centres of the
    // column nearest the sample, so which voxels it counts is exact.
    const double ci = std::floor(centre.x + R * samples[2 * n]), cj = std::floor(centre.y + R * samples[2 * n + 1]);
    const Vec3 c(ci + 0.5, cj + 0.5, centre.z);
    const double lateral2 = (c.x - centre.x) * (c.x - centre.x) + (c.y - centre.y) * (c.y - centre.y);
    const double half = std::sqrt(std::max(0.0, R * R - lateral2));
    // The chord c + u z, u in [-half, half], where (x - centre).w >= base.
    double u0 = -half, u1 = half;
    const double along = glm::dot(c - centre, w);
    if (std::fabs(w.z) < 1e-12)
    {
      if (along < base)
        continue;
    }
    else if (w.z > 0.0)
      u0 = std::max(u0, (base - along) / w.z);
    else
      u1 = std::min(u1, (base - along) / w.z);
    if (!(u0 <= u1))
      continue;
    const double k0 = std::ceil(c.z + u0 - 0.5), k1 = std::floor(c.z + u1 - 0.5);
    if (!(k0 <= k1))
      continue;
    // Outside the grid is empty: the indices are clamped to just outside
    // it before the casts (CountBits counts nothing there).
    auto index = [](double v, int n) { return static_cast<int>(std::min(static_cast<double>(n), std::max(-1.0, v))); };
    const int i = index(ci, grid.nx), j = index(cj, grid.ny), first = index(k0, grid.slices),
              last = index(k1, grid.slices);
    const double ratio = grid.CountBits(i, j, first, last) / (k1 - k0 + 1.0);
    const double solidRatio = solids ? solids->CountBits(i, j, first, last) / (k1 - k0 + 1.0) : 0.0;
    const Vec3 near = c + Vec3(0, 0, u0) - centre, far = c + Vec3(0, 0, u1) - centre;
    const double dm = std::max(0.5 * (glm::length(near) + glm::length(far)), 1e-12);
    if (paper)
    {
      sum += ratio / ((dm * h) * (dm * h)); // world units, as the seed's Table 3.1
      solidSum += solidRatio / ((dm * h) * (dm * h));
      weights += 1.0;
      continue;
    }
    const Vec3 middle = 0.5 * (near + far);
    const double ml = glm::length(middle);
    // The angular weight: the cosine to the normal (the surface
    // definition), or the seed's sine to the tangent.
    const double angular = !(ml > 0.0) ? 0.0
      : cosine                          ? std::max(0.0, glm::dot(w, middle) / ml)
      : line                            ? glm::length(glm::cross(T, middle)) / ml
                                        : 1.0;
    const double weight = angular / ((dm / R) * (dm / R));
    sum += weight * ratio;
    solidSum += weight * solidRatio;
    weights += weight;
  }
  if (solidOccupancy)
    *solidOccupancy = weights > 0.0 ? solidSum / weights : 0.0;
  return weights > 0.0 ? sum / weights : 0.0;
}

double LineVoxelExtinction(double rho)
{
  // Rendering/Tool/Benchmark/line_extinction.py, 20 000 random tubes and
  // rays per radius: the sigma whose mean exp(-sigma l) over the rays'
  // chords l through the voxelized tube equals the exact tube's mean
  // transmittance. A line drawn as a line (rho 0) is the supercover against
  // a tube of its cross-section (radius 0.691); a tube thinner than a
  // voxel tends to transparent (sigma 0 at rho 0+).
  if (!(rho > 0.0))
    return 2.276;
  static constexpr double Rho[] = { 0.0, 0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 2.0, 3.0, 4.0, 6.0 };
  static constexpr double Sigma[] = { 0.0, 0.341, 0.985, 2.214, 1.996, 1.701, 1.623, 1.636, 1.540, 1.580, 1.630 };
  constexpr int Count = static_cast<int>(sizeof(Rho) / sizeof(Rho[0]));
  if (rho >= Rho[Count - 1])
    return Sigma[Count - 1];
  int i = 1;
  while (Rho[i] < rho)
    ++i;
  const double t = (rho - Rho[i - 1]) / (Rho[i] - Rho[i - 1]);
  return Sigma[i - 1] + t * (Sigma[i] - Sigma[i - 1]);
}

double LineRaysOf(const BitGrid& grid, const LineAOSettings& settings, const double* samples,
  const LineHalfBall& ball, const BitGrid* solids)
{
  const double R = settings.radius / grid.voxel;
  const double sigma = settings.strength * LineVoxelExtinction(settings.tubeRadius / grid.voxel);
  const Vec3 o = LoadVec3(ball.centre), w = LoadVec3(ball.w);
  const Vec3 t1 = glm::normalize(glm::cross(w, std::fabs(w.x) < 0.6 ? Vec3(1, 0, 0) : Vec3(0, 1, 0)));
  const Vec3 t2 = glm::cross(w, t1);
  // The pixel's set turns the Hammersley points (Cranley-Patterson).
  const double shiftU = 0.5 * (samples[0] + 1.0), shiftV = 0.5 * (samples[1] + 1.0);
  const int count = settings.samples;
  const int dims[3] = { grid.nx, grid.ny, grid.slices };
  // A centre outside the grid padded by R sees nothing (and a NaN or huge
  // one would overflow the cell indices).
  for (int c = 0; c < 3; ++c)
    if (!(o[c] > -R - 1.0 && o[c] < dims[c] + R + 1.0))
      return 1.0;
  // A walk visits at most this many cells inside the grid (it stops once
  // outside and moving away): the work is bounded by the grid, not R.
  const int cells = dims[0] + dims[1] + dims[2] + 3;
  double sum = 0.0;
  for (int n = 0; n < count; ++n)
  {
    double local[3];
    HemisphereDirection(n, count, shiftU, shiftV, true, local);
    const Vec3 d = local[0] * t1 + local[1] * t2 + local[2] * w;
    // Amanatides and Woo's walk through the unit voxels from o to R.
    int cell[3], step[3];
    double next[3], delta[3];
    for (int c = 0; c < 3; ++c)
    {
      cell[c] = static_cast<int>(std::floor(o[c]));
      step[c] = d[c] > 0.0 ? 1 : -1;
      const double magnitude = std::fabs(d[c]);
      delta[c] = magnitude > 1e-12 ? 1.0 / magnitude : std::numeric_limits<double>::infinity();
      next[c] = magnitude > 1e-12 ? (d[c] > 0.0 ? cell[c] + 1.0 - o[c] : o[c] - cell[c]) / magnitude
                                  : std::numeric_limits<double>::infinity();
    }
    double t = 0.0, depth = 0.0;
    bool blocked = false;
    for (int visited = 0; t < R && visited < cells; ++visited)
    {
      const int c = next[0] <= next[1] && next[0] <= next[2] ? 0 : next[1] <= next[2] ? 1 : 2;
      const double exit = std::min(next[c], R);
      bool away = false;
      for (int a = 0; a < 3; ++a)
        away = away || (cell[a] < 0 && step[a] < 0) || (cell[a] >= dims[a] && step[a] > 0);
      if (away)
        break; // (outside, leaving: the rest of the ray is empty)
      if (cell[0] >= 0 && cell[1] >= 0 && cell[2] >= 0 && cell[0] < dims[0] && cell[1] < dims[1] &&
        cell[2] < dims[2] &&
        glm::dot(Vec3(cell[0] + 0.5, cell[1] + 0.5, cell[2] + 0.5) - o, w) >= ball.base)
      {
        // A mesh's voxels overhang its surface by up to a voxel: a solid
        // stops the ray from LineSolidOffset on (a line beside a wall
        // would have every ray stopped at once).
        if (solids && t >= LineSolidOffset && solids->Bit(cell[0], cell[1], cell[2]))
        {
          blocked = true;
          break;
        }
        // A line voxel dims the ray from voxelOffset on: a tube's voxels
        // overhang its surface too.
        if (grid.Bit(cell[0], cell[1], cell[2]) && exit > settings.voxelOffset)
          depth += exit - std::max(t, settings.voxelOffset);
      }
      t = exit;
      next[c] += delta[c];
      cell[c] += step[c];
    }
    if (!blocked)
      sum += std::exp(-sigma * depth);
  }
  return sum / count;
}

double LineOccupancyAt(const BitGrid& grid, const LineAOSettings& settings, const double* samples,
  const double axisPoint[3], const double tangent[3], const double view[3], const double* surface,
  const double* normal, const BitGrid* solids, double* solidOccupancy)
{
  return LineOccupancyOf(grid, settings, samples,
    LineHalfBallAt(grid, settings, axisPoint, tangent, view, surface, normal), solids, solidOccupancy);
}

double LineOcclusionScale(const LineAOSettings& settings, double voxel)
{
  // A thin tube blocks rays in proportion to its width (2 r) but fills a
  // half ball in proportion to its cross-section (its voxelized one: the
  // tube's, or at least a supercover's 1.5 voxels^2, a unit cube's mean
  // projected area): occlusion ~ c R r / A occupancy. Lines drawn as lines
  // (r = 0) are tubes as wide as their supercover. c: docs/lines.md.
  const double area = std::max(Pi * settings.tubeRadius * settings.tubeRadius, SupercoverArea * voxel * voxel);
  const double r = settings.tubeRadius > 0.0 ? settings.tubeRadius : std::sqrt(area / Pi);
  return OcclusionCalibration * Pi * settings.radius * r / area;
}

double LineAOFromOccupancy(const LineAOSettings& settings, double voxel, double occupancy)
{
  if (settings.weights == LineAOWeights::Paper)
    return 1.0 - std::min(1.0, std::max(0.0, settings.aoFactor * occupancy));
  return std::exp(-settings.strength * LineOcclusionScale(settings, voxel) * occupancy);
}

double LineAOAt(const BitGrid& grid, const LineAOSettings& settings, const double* samples,
  const double axisPoint[3], const double tangent[3], const double view[3], const double* surface,
  const double* normal)
{
  if (settings.estimator == LineAOEstimator::Rays)
    return LineRaysOf(
      grid, settings, samples, LineHalfBallAt(grid, settings, axisPoint, tangent, view, surface, normal));
  return LineAOFromOccupancy(settings, grid.voxel,
    LineOccupancyAt(grid, settings, samples, axisPoint, tangent, view, surface, normal));
}

std::string CheckLineAOFrame(const BitGrid& grid, const LineAOSettings& settings, const LineFrame& frame,
  const BitGrid* solids, bool bitsElsewhere)
{
  std::string error = settings.Validate();
  if (!error.empty())
    return error;
  const std::size_t words = static_cast<std::size_t>(grid.nx) * grid.ny * grid.words;
  if (grid.IsFrustum() || grid.nx < 1 || grid.ny < 1 || grid.words < 1 ||
    (!bitsElsewhere && (grid.bits.empty() || grid.bits.size() != words)))
    return "line AO needs a voxelized world or eye grid";
  if (solids &&
    (solids->nx != grid.nx || solids->ny != grid.ny || solids->slices != grid.slices ||
      solids->voxel != grid.voxel || solids->origin != grid.origin || solids->axes != grid.axes ||
      solids->bits.size() != words))
    return "the solids' grid is not planned as the lines' grid";
  const std::size_t pixels = static_cast<std::size_t>(frame.width) * frame.height;
  if (frame.width < 0 || frame.height < 0 || frame.segment.size() != pixels || frame.axis.size() != 3 * pixels ||
    frame.tangent.size() != 3 * pixels || frame.view.size() != 3 * pixels)
    return "the line G-buffer's arrays do not match its size";
  return std::string();
}

double LineFrameAO(const LineAOSettings& settings, double voxel, double occupancy, double solidOccupancy)
{
  // Solid occluders fill what they occlude: their occupancy as it is.
  return LineAOFromOccupancy(settings, voxel, occupancy) * (1.0 - std::min(1.0, solidOccupancy));
}

bool LineAOFrame(const BitGrid& grid, const LineAOSettings& settings, LineFrame& frame,
  std::string& error, const BitGrid* solids)
{
  error = CheckLineAOFrame(grid, settings, frame, solids);
  if (!error.empty())
    return false;
  const std::size_t pixels = static_cast<std::size_t>(frame.width) * frame.height;
  frame.ao.assign(pixels, std::numeric_limits<double>::quiet_NaN());
  const std::vector<double> samples = LineAOSamples(settings.samples, settings.seed);
  const int width = frame.width;
  ParallelFor(pixels, settings.threads, [&](std::size_t p) {
    if (frame.segment[p] < 0)
      return;
    const int set = LineSampleSet(static_cast<int>(p % width), static_cast<int>(p / width));
    const double* sample = &samples[static_cast<std::size_t>(set) * 2 * settings.samples];
    if (settings.estimator == LineAOEstimator::Rays)
    {
      frame.ao[p] = LineRaysOf(grid, settings, sample, LineHalfBallOfPixel(grid, settings, frame, p), solids);
      return;
    }
    // One walk of the prisms counts both grids.
    double solidOccupancy = 0.0;
    const double occupancy = LineOccupancyOf(grid, settings, sample,
      LineHalfBallOfPixel(grid, settings, frame, p), solids, &solidOccupancy);
    frame.ao[p] = LineFrameAO(settings, grid.voxel, occupancy, solidOccupancy);
  });
  return true;
}

}
