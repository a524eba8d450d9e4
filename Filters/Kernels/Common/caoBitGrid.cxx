#include "caoBitGrid.h"

#include <algorithm>
#include <cmath>

namespace cao
{

int BitGrid::CountBits(int i, int j, int k0, int k1) const
{
  if (i < 0 || j < 0 || i >= this->nx || j >= this->ny)
    return 0;
  k0 = std::max(k0, 0);
  k1 = std::min(k1, this->slices - 1);
  if (k1 < k0)
    return 0;
  const std::uint32_t* column = &this->bits[(static_cast<std::size_t>(j) * this->nx + i) * this->words];
  int count = 0;
  for (int w = k0 >> 5; w <= (k1 >> 5); ++w)
  {
    std::uint32_t word = column[w];
    const int lo = w == (k0 >> 5) ? (k0 & 31) : 0, hi = w == (k1 >> 5) ? (k1 & 31) : 31;
    word &= (~0u << lo) & (~0u >> (31 - hi)); // bits lo..hi (bitfieldExtract's range)
    count += __builtin_popcount(word);        // bitCount
  }
  return count;
}

std::int64_t BitGrid::CountAll() const
{
  std::int64_t n = 0;
  for (std::uint32_t w : this->bits)
    n += __builtin_popcount(w);
  return n;
}

bool PlanGrid(const std::array<double, 6>& bounds, double padding, int slices, BitGrid& grid,
  std::string& error)
{
  if (slices < 32 || slices > 1024 || slices % 32 != 0)
  {
    error = "depth slices must be 32..1024 and a multiple of 32 (got " + std::to_string(slices) + ")";
    return false;
  }
  if (!(padding >= 0.0) || !std::isfinite(padding))
  {
    error = "the grid padding must be finite and not negative";
    return false;
  }
  double size = 0.0, diagonal2 = 0.0;
  for (int d = 0; d < 3; ++d)
  {
    if (!std::isfinite(bounds[2 * d]) || !std::isfinite(bounds[2 * d + 1]) ||
      bounds[2 * d + 1] < bounds[2 * d])
    {
      error = "the grid's bounds are empty or not finite";
      return false;
    }
    diagonal2 += (bounds[2 * d + 1] - bounds[2 * d]) * (bounds[2 * d + 1] - bounds[2 * d]);
  }
  // Nothing is set beyond the meshes, and a cone's samples outside the grid
  // read empty: padding wider than half the bounds' diagonal only coarsens
  // the voxels (a radius 20 x the scene's made them 20 x coarser, and the
  // AO all but vanished). Radii up to 0.48 x the diagonal keep their grid.
  if (diagonal2 > 0.0)
    padding = std::min(padding, 0.5 * std::sqrt(diagonal2));
  for (int d = 0; d < 3; ++d)
    size = std::max(size, bounds[2 * d + 1] - bounds[2 * d] + 2.0 * padding);
  if (!(size > 0.0))
  {
    error = "the meshes have no extent";
    return false;
  }
  grid = BitGrid();
  grid.slices = slices;
  grid.words = slices / 32;
  grid.voxel = size / slices;
  const double h = grid.voxel;
  const double nxd = std::ceil((bounds[1] - bounds[0] + 2.0 * padding) / h - 1e-9);
  const double nyd = std::ceil((bounds[3] - bounds[2] + 2.0 * padding) / h - 1e-9);
  grid.nx = std::max(1, static_cast<int>(nxd));
  grid.ny = std::max(1, static_cast<int>(nyd));
  if (static_cast<std::int64_t>(grid.nx) * grid.ny > BitGrid::MaximumColumns)
  {
    error = "the grid would have " + std::to_string(static_cast<std::int64_t>(grid.nx) * grid.ny) +
      " columns; at most " + std::to_string(BitGrid::MaximumColumns);
    return false;
  }
  // Centred on the bounds' centre in x and y; z starts at the padded bottom.
  grid.origin = { { 0.5 * (bounds[0] + bounds[1]) - 0.5 * grid.nx * h,
    0.5 * (bounds[2] + bounds[3]) - 0.5 * grid.ny * h, bounds[4] - padding } };
  return true;
}

void BitGrid::ToGrid(const double w[3], double out[3]) const
{
  const double* a = this->axes.data();
  for (int r = 0; r < 3; ++r)
    out[r] = a[3 * r] * w[0] + a[3 * r + 1] * w[1] + a[3 * r + 2] * w[2];
}

void BitGrid::ToWorld(const double g[3], double out[3]) const
{
  const double* a = this->axes.data();
  for (int c = 0; c < 3; ++c)
    out[c] = a[c] * g[0] + a[3 + c] * g[1] + a[6 + c] * g[2];
}

bool EyeAxes(const double right[3], const double up[3], std::array<double, 9>& axes,
  std::string& error)
{
  double x[3] = { right[0], right[1], right[2] }, y[3] = { up[0], up[1], up[2] };
  const double lx = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
  if (!(lx > 0.0) || !std::isfinite(lx))
  {
    error = "the camera's frame is degenerate";
    return false;
  }
  for (double& v : x)
    v /= lx;
  const double d = x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
  for (int k = 0; k < 3; ++k)
    y[k] -= d * x[k];
  const double ly = std::sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]);
  if (!(ly > 1e-12 * lx) || !std::isfinite(ly))
  {
    error = "the camera's frame is degenerate";
    return false;
  }
  for (double& v : y)
    v /= ly;
  axes = { { x[0], x[1], x[2], y[0], y[1], y[2], x[1] * y[2] - x[2] * y[1],
    x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0] } };
  return true;
}

bool BitGrid::FrustumCell(const double q[3], int& i, int& j, double& s) const
{
  double c[4];
  GridToClip(this->frustum.toClip, q, c);
  if (this->frustum.perspective && !(c[3] > 0.0))
    return false;
  const double iw = 1.0 / c[3];
  const double x = (c[0] * iw + 1.0) * 0.5 * this->nx, y = (c[1] * iw + 1.0) * 0.5 * this->ny;
  if (!(x >= 0.0 && y >= 0.0 && x < this->nx && y < this->ny))
    return false;
  i = static_cast<int>(x);
  j = static_cast<int>(y);
  const std::size_t col = static_cast<std::size_t>(j) * this->nx + i;
  const double depth = this->frustum.perspective ? c[3] : c[2] * iw;
  s = (depth - this->frustum.nearDepth[col]) * this->frustum.slicesPerDepth[col];
  return true;
}

double BitGrid::FrustumVoxel(const double q[3], bool larger) const
{
  double c[4];
  GridToClip(this->frustum.toClip, q, c);
  const double* m = this->frustum.toClip.data();
  // A pixel's width: d(ndc x)/d(grid x) = (m0 w - x m12) / w^2.
  const double rate = std::fabs((m[0] * c[3] - c[0] * m[12]) / (c[3] * c[3]));
  const double pixel = rate > 0.0 ? 2.0 / (this->nx * rate) : this->voxel;
  int i, j;
  double s;
  double slice = this->voxel;
  if (this->FrustumCell(q, i, j, s))
    slice = this->frustum.worldPerDepth /
      this->frustum.slicesPerDepth[static_cast<std::size_t>(j) * this->nx + i];
  const double v = larger ? std::max(pixel, slice) : std::min(pixel, slice);
  return v > 0.0 && std::isfinite(v) ? v : this->voxel;
}

}
