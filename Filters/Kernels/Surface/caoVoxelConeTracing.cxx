#include "caoVoxelConeTracing.h"

#include "caoOpacity.h"
#include "caoParallelFor.h"
#include "caoScreenSpaceAO.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <sstream>
#include <thread>

namespace cao
{
namespace
{
constexpr double Pi = 3.14159265358979323846;
}

int VCTSettings::EffectiveSpheres() const
{
  switch (this->quality)
  {
    case Quality::Low:
      return 3;
    case Quality::Medium:
      return 5;
    case Quality::High:
      return 7;
    default:
      return this->spheres;
  }
}

int VCTSettings::EffectivePrisms() const
{
  switch (this->quality)
  {
    case Quality::Low:
      return 3;
    case Quality::Medium:
      return 6;
    case Quality::High:
      return 12;
    default:
      return this->prisms;
  }
}

std::string VCTSettings::Validate() const
{
  if (!ValidQuality(this->quality))
    return "unknown quality";
  if (this->spheres < 1 || this->spheres > 16)
    return "spheres per cone must be 1..16 (got " + std::to_string(this->spheres) + ")";
  if (this->prisms < 1 || this->prisms > MaximumPrisms)
    return "prisms per sphere must be 1.." + std::to_string(MaximumPrisms) + " (got " +
      std::to_string(this->prisms) + ")";
  if (!(this->coneHalfAngle >= 5.0 && this->coneHalfAngle <= 45.0))
    return "the cone half-angle must be 5..45 degrees";
  if (this->slices < 32 || this->slices > 1024 || this->slices % 32 != 0)
    return "depth slices must be 32..1024 and a multiple of 32 (got " + std::to_string(this->slices) + ")";
  if (!(this->radius > 0.0) || !std::isfinite(this->radius))
    return "the radius must be positive and finite";
  if (!(this->apexOffset >= 0.0 && this->apexOffset <= 4.0))
    return "the apex offset must be 0..4 voxels";
  if (this->occupancy != VCTOccupancy::Rays && this->occupancy != VCTOccupancy::Volume)
    return "unknown occupancy (rays or volume)";
  if (!(this->rayStep >= 0.1 && this->rayStep <= 1.0))
    return "the ray step must be 0.1..1 voxel";
  if (!(this->filterTolerance > 0.0 && this->filterTolerance <= 10.0))
    return "the filter tolerance must be in (0, 10] radii";
  return std::string();
}

const char* VCTOccupancyName(VCTOccupancy occupancy)
{
  return occupancy == VCTOccupancy::Volume ? "volume" : "rays";
}

bool ParseVCTOccupancy(const std::string& text, VCTOccupancy& occupancy)
{
  for (VCTOccupancy o : { VCTOccupancy::Rays, VCTOccupancy::Volume })
    if (text == VCTOccupancyName(o))
    {
      occupancy = o;
      return true;
    }
  return false;
}

std::string VCTUnresolvedRadius(double radius, const BitGrid& grid)
{
  if (!(grid.voxel > 0.0) || !(radius < grid.voxel))
    return std::string();
  std::ostringstream o;
  o << "the AO radius " << radius << " is under a voxel of the grid (" << grid.voxel
    << "): the cones would read only the surface they start from, so Voxel Cones gives no AO; "
       "raise the radius or the slices";
  return o.str();
}

bool BuildVCTPlan(const VCTSettings& settings, const BitGrid& grid, VCTPlan& plan,
  std::string& error)
{
  error = settings.Validate();
  if (!error.empty())
    return false;
  if (grid.nx < 1 || grid.slices < 32)
  {
    error = "the grid is empty (voxelize first)";
    return false;
  }
  plan = VCTPlan();
  // One cone along the normal and five at 60 degrees, 72 degrees apart.
  plan.cones.push_back({ { 0.0, 0.0, 1.0 } });
  for (int m = 0; m < 5; ++m)
  {
    const double theta = Pi / 3.0, phi = 2.0 * Pi * m / 5.0;
    plan.cones.push_back({ { std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
      std::cos(theta) } });
  }
  if (settings.weights == ConeWeights::Cosine)
  {
    // The cosine-weighted shares of the cap theta < 30 degrees (sin^2 30) and
    // of the five sectors of the ring beyond it.
    plan.coneWeights = { 0.25, 0.15, 0.15, 0.15, 0.15, 0.15 };
  }
  else
    plan.coneWeights.assign(6, 1.0 / 6.0);
  // Tangent spheres along a cone, the last ending at R.
  const double s = std::sin(settings.coneHalfAngle * Pi / 180.0);
  const double q = (1.0 + s) / (1.0 - s);
  const double h = grid.voxel;
  int n = settings.EffectiveSpheres();
  const double last = settings.radius / (1.0 + s);
  while (n > 1 && s * last / std::pow(q, n - 1) < h)
    --n; // the first sphere would be under a voxel
  for (int k = 0; k < n; ++k)
  {
    const double t = last / std::pow(q, n - 1 - k);
    plan.spheres.push_back({ t, s * t });
  }
  // A progressive best-candidate (Mitchell) Poisson-disk pattern: the
  // centre first, each next point the farthest of 64 candidates from
  // those before (fixed seed: the same pattern everywhere).
  const int prisms = settings.EffectivePrisms();
  plan.disk.push_back({ { 0.0, 0.0 } });
  std::uint64_t state = 0x9e3779b97f4a7c15ull;
  auto next = [&state]() {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(state >> 11) * (1.0 / 9007199254740992.0);
  };
  while (static_cast<int>(plan.disk.size()) < prisms)
  {
    std::array<double, 2> best{ { 0, 0 } };
    double bestDistance = -1.0;
    for (int c = 0; c < 64; ++c)
    {
      const double r = std::sqrt(next()), a = 2.0 * Pi * next();
      const std::array<double, 2> cand{ { r * std::cos(a), r * std::sin(a) } };
      double nearest = 1e30;
      for (const auto& d : plan.disk)
        nearest = std::min(nearest, (cand[0] - d[0]) * (cand[0] - d[0]) + (cand[1] - d[1]) * (cand[1] - d[1]));
      if (nearest > bestDistance)
      {
        bestDistance = nearest;
        best = cand;
      }
    }
    plan.disk.push_back(best);
  }
  plan.apexOffset = settings.apexOffset * h;
  plan.occupancy = settings.occupancy;
  plan.rayStep = settings.rayStep * h;
  plan.coneTangent = std::tan(settings.coneHalfAngle * Pi / 180.0);
  plan.interleave = settings.interleave;
  plan.filterTolerance = settings.filterTolerance * settings.radius;
  plan.filterReach = settings.radius;
  return true;
}

layout::VCTParams MakeVCTParams(const BitGrid& grid, const VCTPlan& plan, int points, int rowLength)
{
  layout::VCTParams v{};
  v.grid = { grid.nx, grid.ny, grid.slices, grid.words };
  v.origin = { static_cast<float>(grid.origin[0]), static_cast<float>(grid.origin[1]),
    static_cast<float>(grid.origin[2]), static_cast<float>(1.0 / grid.voxel) };
  const int cones = std::min<int>(static_cast<int>(plan.cones.size()), CAO_VCT_MAX_CONES);
  const int spheres = std::min<int>(static_cast<int>(plan.spheres.size()), CAO_VCT_MAX_SPHERES);
  const int prisms = std::min<int>(static_cast<int>(plan.disk.size()), CAO_VCT_MAX_PRISMS);
  v.counts = { cones, spheres, prisms, points };
  v.apex = { static_cast<float>(plan.apexOffset), plan.occupancy == VCTOccupancy::Rays ? 1.0f : 0.0f,
    static_cast<float>(plan.rayStep), static_cast<float>(plan.coneTangent) };
  for (int c = 0; c < cones; ++c)
    v.cones[c] = { static_cast<float>(plan.cones[c][0]), static_cast<float>(plan.cones[c][1]),
      static_cast<float>(plan.cones[c][2]), static_cast<float>(plan.coneWeights[c]) };
  for (int k = 0; k < spheres; ++k)
    v.spheres[k] = { static_cast<float>(plan.spheres[k].t), static_cast<float>(plan.spheres[k].r), 0, 0 };
  for (int k = 0; k < prisms; ++k)
  {
    const double x = plan.disk[k][0], y = plan.disk[k][1];
    v.disk[k] = { static_cast<float>(x), static_cast<float>(y),
      static_cast<float>(std::sqrt(std::max(0.0, 1.0 - x * x - y * y))), 0 };
  }
  // The frustum grid's projection (its columns' depths go in a buffer).
  if (grid.IsFrustum())
  {
    for (int r = 0; r < 4; ++r)
      v.frustum[r] = { static_cast<float>(grid.frustum.toClip[4 * r]), static_cast<float>(grid.frustum.toClip[4 * r + 1]),
        static_cast<float>(grid.frustum.toClip[4 * r + 2]), static_cast<float>(grid.frustum.toClip[4 * r + 3]) };
    v.frustum[4] = { 1.0f, grid.frustum.perspective ? 1.0f : 0.0f, static_cast<float>(grid.frustum.worldPerDepth), 0.0f };
  }
  // The occluding volumes, their opacity one after another in plan order;
  // each maps the grid's frame to its voxel index: worldToIndex * axes^T.
  const int volumes = std::min<int>(static_cast<int>(plan.volumes.size()), CAO_VCT_MAX_VOLUMES);
  v.volumeCount = { volumes, plan.interleave ? std::max(0, rowLength) : 0, 0, 0 };
  double rotation[16];
  VCTPatternRotations(rotation);
  for (int r = 0; r < 4; ++r)
    v.rotations[r] = { static_cast<float>(rotation[4 * r]), static_cast<float>(rotation[4 * r + 1]),
      static_cast<float>(rotation[4 * r + 2]), static_cast<float>(rotation[4 * r + 3]) };
  std::int64_t offset = 0;
  for (int k = 0; k < volumes; ++k)
  {
    const OpacityVolume& volume = *plan.volumes[k];
    const double* m = volume.worldToIndex.data();
    const double* a = grid.axes.data();
    layout::VCTVolume& out = v.volumes[k];
    for (int r = 0; r < 3; ++r)
    {
      double row[4];
      for (int c = 0; c < 3; ++c)
        row[c] = m[4 * r] * a[3 * c] + m[4 * r + 1] * a[3 * c + 1] + m[4 * r + 2] * a[3 * c + 2];
      row[3] = m[4 * r + 3];
      out.toIndex[r] = { static_cast<float>(row[0]), static_cast<float>(row[1]), static_cast<float>(row[2]),
        static_cast<float>(row[3]) };
    }
    out.dims = { volume.dims[0], volume.dims[1], volume.dims[2], static_cast<std::int32_t>(offset) };
    out.scalars = { static_cast<float>(1.0 / volume.unitDistance), 0, 0, 0 };
    offset += static_cast<std::int64_t>(volume.alpha.size());
  }
  return v;
}

namespace
{
/// (x, y) turned in their plane: x c + y s, y c - x s (the GLSL's Turn).
void Turn(double c, double s, double x[3], double y[3])
{
  for (int d = 0; d < 3; ++d)
  {
    const double a = x[d], b = y[d];
    x[d] = a * c + b * s;
    y[d] = b * c - a * s;
  }
}

/// An orthonormal frame (x, y) around the unit vector n (Duff et al. 2017),
/// as the GLSL's Frame.
void Frame(const double n[3], double x[3], double y[3])
{
  const double sign = n[2] >= 0.0 ? 1.0 : -1.0;
  const double a = -1.0 / (sign + n[2]);
  const double b = n[0] * n[1] * a;
  x[0] = 1.0 + sign * n[0] * n[0] * a;
  x[1] = sign * b;
  x[2] = -sign * n[0];
  y[0] = b;
  y[1] = sign + n[1] * n[1] * a;
  y[2] = -n[1];
}

}

/// A cone's occlusion by rays (grid coordinates): one ray per prism point
/// of the unit disk, apex + tau (dir + tan(beta) (x u + y v)), tau from the
/// first sphere's near side (on a world or eye grid at most 3 voxels out)
/// to the last one's far side (R from the apex),
/// sampled at the midpoints of steps of at most plan.rayStep; the
/// cosine-weighted share of the rays that meet a set voxel (a ray's weight:
/// its cosine with n). The GLSL's RayOcclusion is the same in float.
/// The frustum grid samples its columns instead (FrustumCell), at most
/// `rayStep` (the plan's, scaled to the local voxel) apart.
double RayOcclusion(const BitGrid& grid, const VCTPlan& plan, const double apex[3], const double n[3],
  const double dir[3], const double u[3], const double v[3], double rayStep)
{
  const double inv = 1.0 / grid.voxel;
  const bool frustum = grid.IsFrustum();
  const VCTPlan::Sphere& first = plan.spheres.front();
  // From the first sphere's near side, which is 1 to 3 voxels out when the
  // voxel limits the spheres; when their number does (a radius much larger
  // than the voxels), from 3 voxels out, so that what is near is not skipped.
  const double nearSide = first.t - first.r;
  const double t0 = frustum ? nearSide : std::min(nearSide, 3.0 * grid.voxel);
  const double t1 = plan.spheres.back().t + plan.spheres.back().r;
  // The grid's box (world or eye grid): samples outside it read empty, so
  // the march visits only the steps that can be inside (the same samples).
  const double box[6] = { grid.origin[0], grid.origin[0] + grid.nx * grid.voxel, grid.origin[1],
    grid.origin[1] + grid.ny * grid.voxel, grid.origin[2], grid.origin[2] + grid.slices * grid.voxel };
  double blocked = 0.0, all = 0.0;
  for (const auto& sample : plan.disk)
  {
    double ray[3];
    for (int d = 0; d < 3; ++d)
      ray[d] = dir[d] + plan.coneTangent * (sample[0] * u[d] + sample[1] * v[d]);
    const double length = std::sqrt(ray[0] * ray[0] + ray[1] * ray[1] + ray[2] * ray[2]);
    const double weight = std::max(0.0, (ray[0] * n[0] + ray[1] * n[1] + ray[2] * n[2]) / length);
    all += weight;
    const int steps = std::max(1, static_cast<int>(std::ceil((t1 - t0) * length / rayStep)));
    const double step = (t1 - t0) / steps;
    int mBegin = 0, mEnd = steps;
    if (!frustum)
    {
      double enter = t0, exit = t1;
      for (int d = 0; d < 3; ++d)
      {
        if (ray[d] == 0.0)
        {
          if (apex[d] < box[2 * d] || apex[d] > box[2 * d + 1])
            exit = -1.0; // parallel to the slab and outside it
          continue;
        }
        const double a = (box[2 * d] - apex[d]) / ray[d], b = (box[2 * d + 1] - apex[d]) / ray[d];
        enter = std::max(enter, std::min(a, b));
        exit = std::min(exit, std::max(a, b));
      }
      if (exit < enter - step)
        continue; // the ray never enters the grid (by more than a step's rounding)
      // One step of slack on each side: the samples there are tested as
      // before, so the result is the full march's.
      mBegin = std::max(0, static_cast<int>(std::floor((enter - t0) / step)) - 1);
      mEnd = std::min(steps, static_cast<int>(std::ceil((exit - t0) / step)) + 1);
    }
    for (int m = mBegin; m < mEnd; ++m)
    {
      const double tau = t0 + (m + 0.5) * step;
      if (frustum)
      {
        const double q[3] = { apex[0] + tau * ray[0], apex[1] + tau * ray[1], apex[2] + tau * ray[2] };
        int i, j;
        double sl;
        if (grid.FrustumCell(q, i, j, sl) && sl >= 0.0 && sl < grid.slices &&
          grid.Bit(i, j, static_cast<int>(sl)))
        {
          blocked += weight;
          break;
        }
        continue;
      }
      const int i = static_cast<int>(std::floor((apex[0] + tau * ray[0] - grid.origin[0]) * inv));
      const int j = static_cast<int>(std::floor((apex[1] + tau * ray[1] - grid.origin[1]) * inv));
      const int k = static_cast<int>(std::floor((apex[2] + tau * ray[2] - grid.origin[2]) * inv));
      if (i >= 0 && j >= 0 && k >= 0 && i < grid.nx && j < grid.ny && k < grid.slices && grid.Bit(i, j, k))
      {
        blocked += weight;
        break;
      }
    }
  }
  return all > 0.0 ? blocked / all : 0.0;
}

namespace
{

/// A sphere's occupancy (seed 000): the set bits over the bits counted in
/// the prisms (z columns) through its disk points, each limited to the
/// sphere's chord. The GLSL's volume branch is the same in float.
double SphereOccupancy(const BitGrid& grid, const VCTPlan& plan, const double centre[3], double r)
{
  if (grid.IsFrustum())
  {
    // Each prism is the column its disk point falls in, over the slices of
    // the chord's depths (seed 000's prisms in the paper's grid).
    std::int64_t set = 0, total = 0;
    for (const auto& sample : plan.disk)
    {
      const double half = r * std::sqrt(std::max(0.0, 1.0 - sample[0] * sample[0] - sample[1] * sample[1]));
      const double q[3] = { centre[0] + r * sample[0], centre[1] + r * sample[1], centre[2] };
      int i, j;
      double s;
      if (!grid.FrustumCell(q, i, j, s))
        continue; // off the screen: not in the grid, as in the paper
      // The chord along the view, in its column's slices.
      const double ds = half / grid.frustum.worldPerDepth *
        grid.frustum.slicesPerDepth[static_cast<std::size_t>(j) * grid.nx + i];
      const double sn = std::max(-1.0, std::min(s - ds, grid.slices + 1.0));
      const double sf = std::max(-1.0, std::min(s + ds, grid.slices + 1.0));
      int k0 = static_cast<int>(std::ceil(std::min(sn, sf) - 0.5));
      int k1 = static_cast<int>(std::floor(std::max(sn, sf) - 0.5));
      if (k1 < k0)
        k0 = k1 = static_cast<int>(std::floor(std::max(-1.0, std::min(s, grid.slices + 1.0))));
      total += k1 - k0 + 1;
      set += grid.CountBits(i, j, k0, k1);
    }
    return total > 0 ? static_cast<double>(set) / static_cast<double>(total) : 0.0;
  }
  const double h = grid.voxel;
  const double gz = (centre[2] - grid.origin[2]) / h;
  std::int64_t set = 0, total = 0;
  for (const auto& sample : plan.disk)
  {
    const double gx = (centre[0] + r * sample[0] - grid.origin[0]) / h;
    const double gy = (centre[1] + r * sample[1] - grid.origin[1]) / h;
    const int i = static_cast<int>(std::floor(gx)), j = static_cast<int>(std::floor(gy));
    const double half = r * std::sqrt(std::max(0.0, 1.0 - sample[0] * sample[0] - sample[1] * sample[1])) / h;
    // The slices whose centres lie on the chord [gz - half, gz + half].
    int k0 = static_cast<int>(std::ceil(gz - half - 0.5));
    int k1 = static_cast<int>(std::floor(gz + half - 0.5));
    if (k1 < k0)
      k0 = k1 = static_cast<int>(std::floor(gz)); // a chord under a slice: its slice
    total += k1 - k0 + 1;
    set += grid.CountBits(i, j, k0, k1);
  }
  return total > 0 ? static_cast<double>(set) / static_cast<double>(total) : 0.0;
}

/// The volume's opacity over a sphere: its mean at the centre and the prism
/// points (on the disk across the grid's z axis), over the diameter.
double SphereOpacity(const BitGrid& grid, const VCTPlan& plan, const OpacityVolume& volume,
  const double centre[3], double r)
{
  double sum = 0.0, g[3], w[3];
  g[0] = centre[0], g[1] = centre[1], g[2] = centre[2];
  grid.ToWorld(g, w);
  sum += volume.Sample(w);
  for (const auto& sample : plan.disk)
  {
    g[0] = centre[0] + r * sample[0];
    g[1] = centre[1] + r * sample[1];
    grid.ToWorld(g, w);
    sum += volume.Sample(w);
  }
  const double mean = sum / static_cast<double>(plan.disk.size() + 1);
  return CorrectOpacity(mean, 2.0 * r / volume.unitDistance);
}
}

double ConeTraceAO(const BitGrid& grid, const VCTPlan& plan, const double pWorld[3], const double nWorld[3],
  double rotation)
{
  double p[3], n[3];
  grid.ToGrid(pWorld, p);
  grid.ToGrid(nWorld, n);
  double tx[3], ty[3];
  Frame(n, tx, ty);
  const double cosTurn = std::cos(rotation), sinTurn = std::sin(rotation);
  Turn(cosTurn, sinTurn, tx, ty);
  // The frustum grid's voxels grow with depth: the apex offset and the
  // rays' step follow the local voxel.
  // A frustum grid's voxels are a pixel wide and a slice deep, both
  // growing with depth: the apex is lifted by, and the rays sampled at,
  // the local voxel's larger side (measured against the smaller: at 512
  // slices a slice-thin offset over-occludes, bias -0.047 on the shared
  // meshes, and the denser samples cost 1.6 to 5.5 times as much).
  const double apexScale = grid.IsFrustum() ? grid.FrustumVoxel(p, true) / grid.voxel : 1.0;
  const double scale = apexScale;
  double apex[3];
  for (int d = 0; d < 3; ++d)
    apex[d] = p[d] + apexScale * plan.apexOffset * n[d];
  double occlusion = 0.0;
  for (std::size_t c = 0; c < plan.cones.size(); ++c)
  {
    const std::array<double, 3>& l = plan.cones[c];
    double dir[3];
    for (int d = 0; d < 3; ++d)
      dir[d] = l[0] * tx[d] + l[1] * ty[d] + l[2] * n[d];
    double u[3], v[3]; // the rays' frame across the cone's axis
    Frame(dir, u, v);
    Turn(cosTurn, sinTurn, u, v);
    // Rays: the cone's rays at once; volume: each sphere's prisms. Then the
    // volumes' opacity over each sphere.
    const bool rays = plan.occupancy == VCTOccupancy::Rays;
    double open = rays ? 1.0 - RayOcclusion(grid, plan, apex, n, dir, u, v, scale * plan.rayStep) : 1.0;
    for (const VCTPlan::Sphere& sphere : plan.spheres)
    {
      double centre[3];
      for (int d = 0; d < 3; ++d)
        centre[d] = apex[d] + sphere.t * dir[d];
      if (!rays)
        open *= 1.0 - SphereOccupancy(grid, plan, centre, sphere.r);
      for (const OpacityVolume* volume : plan.volumes)
        open *= 1.0 - SphereOpacity(grid, plan, *volume, centre, sphere.r);
    }
    occlusion += plan.coneWeights[c] * (1.0 - open);
  }
  return 1.0 - occlusion;
}

namespace
{
/// Cell c's turn: the 4 x 4 ordered-dither (Bayer) order, so that cells
/// next to each other get steps far apart, over the side cones' period.
double PatternRotation(int c)
{
  static const int order[16] = { 0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5 };
  return 2.0 * Pi / 5.0 * (order[c] + 0.5) / 16.0;
}
}

void VCTPatternRotations(double rotation[16])
{
  for (int c = 0; c < 16; ++c)
    rotation[c] = PatternRotation(c);
}

double VCTPixelRotation(const VCTPlan& plan, std::int64_t k, int width)
{
  if (!plan.interleave || width < 1)
    return 0.0;
  const std::int64_t i = k % width, j = k / width;
  return PatternRotation(static_cast<int>((i & 3) + 4 * (j & 3)));
}

std::vector<double> VCTFilterWeights(const VCTPlan& plan)
{
  return plan.interleave ? std::vector<double>{ 0.5, 1.0, 1.0, 1.0, 0.5 } : std::vector<double>();
}

void FinishVCT(const VCTPlan& plan, SurfaceFrame& frame, int threads)
{
  const std::vector<double> weights = VCTFilterWeights(plan);
  if (!weights.empty())
    DepthAwareFilter(frame, weights, plan.filterTolerance, frame.ao, threads, plan.filterReach);
}

bool VCTFrame(const BitGrid& grid, const VCTPlan& plan, SurfaceFrame& frame, int threads,
  std::string& error)
{
  if (plan.cones.empty() || plan.spheres.empty() || plan.disk.empty())
  {
    error = "the cone-tracing plan is empty";
    return false;
  }
  ParallelFor(frame.triangle.size(), threads, [&](std::size_t i) {
    if (frame.triangle[i] >= 0)
      frame.ao[i] = ConeTraceAO(grid, plan, &frame.position[3 * i], &frame.normal[3 * i],
        VCTPixelRotation(plan, static_cast<std::int64_t>(i), frame.width));
  });
  FinishVCT(plan, frame, threads);
  return true;
}

}
