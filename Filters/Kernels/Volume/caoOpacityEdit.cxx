#include "caoOpacityEdit.h"
#include "caoMemory.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <memory>

namespace cao
{
namespace
{
/// `v` resized to `n`; a new allocation is advised to huge pages before its
/// first touch (a volume's byte mask is 16 MiB for 256^3: 4 096 page
/// faults of several microseconds each on first touch otherwise).
template <class T>
void Resize(std::vector<T>& v, std::size_t n)
{
  if (v.capacity() < n)
  {
    std::vector<T>().swap(v); // (nothing to keep: every element is written before it is read)
    v.reserve(n);
    AdviseHugePages(v.data(), n * sizeof(T));
  }
  v.resize(n);
}

double Since(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
    .count();
}

/// Dilate `in` (0/1 per voxel) along axis `axis` into `out`: out[v] = 1
/// when in[v + o] is 1 for some o in [lo, hi] along that axis (lo <= 0 <=
/// hi). Along x, each output row is the OR of its input row shifted by o
/// (contiguous byte runs the compiler vectorises); along y and z, a running
/// count per column over the window's rows (each input row read twice,
/// not once per offset: 18 offsets at 26 rays and 8 samples, and the
/// dilation cost about 110 of the edit's 200 ms on embryo.slc). `inAny`
/// says which input rows hold a 1, so empty rows cost nothing but their
/// fill, and `outAny` is set for the output.
bool DilateAxis(const int dims[3], int axis, int lo, int hi, const std::uint8_t* in,
  const std::uint8_t* inAny, std::uint8_t* out, std::uint8_t* outAny,
  const ContextualUpdate::ParallelFor& parallel, double p0, double p1)
{
  const std::int64_t nx = dims[0], ny = dims[1], nz = dims[2];
  const std::int64_t rows = ny * nz; // rows of nx voxels
  if (axis == 0)
    return parallel(rows, 64, p0, p1, [&](std::int64_t begin, std::int64_t end) {
      for (std::int64_t row = begin; row < end; ++row)
      {
        std::uint8_t* o = out + row * nx;
        std::fill(o, o + nx, std::uint8_t(0));
        outAny[row] = inAny[row];
        if (!inAny[row])
          continue;
        // o[x] |= in[x + d] where x + d lies inside the row.
        const std::uint8_t* src = in + row * nx;
        for (int d = lo; d <= hi; ++d)
        {
          const std::int64_t x0 = std::max<std::int64_t>(0, -d), x1 = std::min<std::int64_t>(nx, nx - d);
          for (std::int64_t x = x0; x < x1; ++x)
            o[x] |= src[x + d];
        }
      }
    });
  // Along y or z: the rows of one line (fixed z, or fixed y) in order, with
  // a running count per column of the window's set voxels (a row enters at
  // t + hi and leaves after t + lo): two passes over the input instead of
  // one per offset of the window.
  const std::int64_t n = axis == 1 ? ny : nz, lines = axis == 1 ? nz : ny;
  return parallel(lines, 1, p0, p1, [&](std::int64_t begin, std::int64_t end) {
    std::vector<std::uint16_t> count(static_cast<std::size_t>(nx));
    for (std::int64_t line = begin; line < end; ++line)
    {
      const auto rowAt = [&](std::int64_t t) { return axis == 1 ? line * ny + t : t * ny + line; };
      std::fill(count.begin(), count.end(), std::uint16_t(0));
      std::int64_t rowsIn = 0; // rows of the window that hold a set voxel
      const auto add = [&](std::int64_t t, int sign) {
        if (t < 0 || t >= n || !inAny[rowAt(t)])
          return;
        const std::uint8_t* src = in + rowAt(t) * nx;
        std::uint16_t* c = count.data();
        if (sign > 0)
          for (std::int64_t x = 0; x < nx; ++x)
            c[x] = static_cast<std::uint16_t>(c[x] + src[x]);
        else
          for (std::int64_t x = 0; x < nx; ++x)
            c[x] = static_cast<std::uint16_t>(c[x] - src[x]);
        rowsIn += sign;
      };
      for (std::int64_t t = lo; t < hi; ++t)
        add(t, 1);
      for (std::int64_t t = 0; t < n; ++t)
      {
        add(t + hi, 1);
        const std::int64_t row = rowAt(t);
        std::uint8_t* o = out + row * nx;
        if (rowsIn == 0)
        {
          std::fill(o, o + nx, std::uint8_t(0));
          outAny[row] = 0;
        }
        else
        {
          std::uint8_t any = 0;
          const std::uint16_t* c = count.data();
          for (std::int64_t x = 0; x < nx; ++x)
          {
            o[x] = c[x] != 0;
            any |= o[x];
          }
          outAny[row] = any;
        }
        add(t + lo, -1);
      }
    }
  });
}
}

std::uint8_t* PrepareEditMask(OpacityEditScratch& scratch, std::int64_t voxels)
{
  Resize(scratch.mask, static_cast<std::size_t>(std::max<std::int64_t>(0, voxels)));
  return scratch.mask.data();
}

void OpacityFootprint(const LAOPlan& plan, int lo[3], int hi[3])
{
  for (int d = 0; d < 3; ++d)
  {
    lo[d] = 0;
    hi[d] = 0;
  }
  for (const layout::LAOTap& t : plan.taps)
  {
    const int c[3] = { t.cell.x, t.cell.y, t.cell.z };
    for (int d = 0; d < 3; ++d)
    {
      lo[d] = std::min(lo[d], c[d]);
      hi[d] = std::max(hi[d], c[d] + 1); // the upper trilinear corner
    }
  }
}

namespace
{
/// The footprint test over `box` (clamped): `reach` (a byte per box voxel,
/// x fastest) says whether a voxel's footprint holds a box voxel where `a`
/// and `b` differ by bit pattern (-0 and 0, or two NaNs, differ as the
/// march reads them), `rowAny` whether a box row holds any such voxel,
/// `changed` how many voxels differ. Both buffers are written in full.
bool Reach(const LAOPlan& plan, const int boxIn[6], const float* a, const float* b,
  std::vector<std::uint8_t>& reach, std::vector<std::uint8_t>& rowAny, int dims[3],
  std::int64_t& changed, const ContextualUpdate::ParallelFor& parallel,
  OpacityEditScratch* scratch = nullptr, std::int64_t stopAbove = -1)
{
  const layout::LAOMarchBlock& p = plan.params;
  const int full[3] = { p.dims.x, p.dims.y, p.dims.z };
  int box[6];
  for (int d = 0; d < 3; ++d)
  {
    box[2 * d] = std::max(0, boxIn[2 * d]);
    box[2 * d + 1] = std::min(full[d] - 1, boxIn[2 * d + 1]);
    dims[d] = std::max(0, box[2 * d + 1] - box[2 * d] + 1);
  }
  const std::int64_t nx = dims[0], rows = std::int64_t(dims[1]) * dims[2], n = nx * rows;
  changed = 0;
  Resize(reach, static_cast<std::size_t>(n));
  rowAny.resize(static_cast<std::size_t>(rows));
  if (n == 0)
    return true;
  // Two masks of a byte per voxel (every byte written before it is read)
  // and a flag per row: the scratch's when given (resize keeps its pages).
  OpacityEditScratch local;
  OpacityEditScratch& sc = scratch ? *scratch : local;
  // Without `a`, the scratch's mask already says which voxels changed.
  const bool given = !a;
  if (given && (!scratch || sc.mask.size() != static_cast<std::size_t>(n)))
    return false;
  Resize(sc.mask, static_cast<std::size_t>(n));
  sc.any.resize(static_cast<std::size_t>(rows));
  sc.perRow.resize(static_cast<std::size_t>(rows));
  std::uint8_t* mask = sc.mask.data();
  std::vector<std::uint8_t>& any = sc.any;
  std::vector<std::int64_t>& perRow = sc.perRow;
  const std::int64_t sy = full[0], sz = std::int64_t(full[0]) * full[1];
  if (!parallel(rows, 64, 0.0, 0.25, [&](std::int64_t r0, std::int64_t r1) {
        for (std::int64_t r = r0; r < r1; ++r)
        {
          const std::int64_t j = r % dims[1], k = r / dims[1];
          const std::int64_t base = box[0] + (box[2] + j) * sy + (box[4] + k) * sz;
          std::int64_t count = 0;
          if (given)
            for (std::int64_t x = 0; x < nx; ++x)
              count += mask[r * nx + x];
          else
          {
            for (std::int64_t x = 0; x < nx; ++x)
            {
              std::uint32_t u, v;
              std::memcpy(&u, a + base + x, sizeof u);
              std::memcpy(&v, b + base + x, sizeof v);
              const std::uint8_t differs = u != v;
              mask[r * nx + x] = differs;
              count += differs;
            }
          }
          perRow[r] = count;
          any[r] = count > 0;
        }
      }))
    return false;
  for (std::int64_t c : perRow)
    changed += c;
  // (The caller needs no reach when this many changed: it marches all.)
  if (stopAbove >= 0 && changed > stopAbove)
    return true;
  if (changed == 0)
  {
    std::fill(reach.begin(), reach.end(), std::uint8_t(0));
    std::fill(rowAny.begin(), rowAny.end(), std::uint8_t(0));
    return true;
  }
  // A voxel v reads v + o, o in [lo, hi]: v is reached when a differing
  // voxel lies in that box, so the differing set is dilated by [lo, hi].
  int lo[3], hi[3];
  OpacityFootprint(plan, lo, hi);
  return DilateAxis(dims, 0, lo[0], hi[0], mask, any.data(), reach.data(), rowAny.data(),
           parallel, 0.25, 0.5) &&
    DilateAxis(dims, 1, lo[1], hi[1], reach.data(), rowAny.data(), mask, any.data(),
      parallel, 0.5, 0.75) &&
    DilateAxis(dims, 2, lo[2], hi[2], mask, any.data(), reach.data(), rowAny.data(),
      parallel, 0.75, 1.0);
}
}

bool OpacityEditReach(const LAOPlan& plan, const float* before, const float* after,
  std::vector<std::int64_t>& reached, std::int64_t& changed,
  const ContextualUpdate::ParallelFor& parallel, OpacityEditScratch* scratch, std::int64_t stopAbove)
{
  const layout::LAOMarchBlock& p = plan.params;
  const int whole[6] = { 0, p.dims.x - 1, 0, p.dims.y - 1, 0, p.dims.z - 1 };
  std::vector<std::uint8_t> localReach, localRowAny;
  std::vector<std::uint8_t>& reach = scratch ? scratch->reach : localReach;
  std::vector<std::uint8_t>& rowAny = scratch ? scratch->rowAny : localRowAny;
  int dims[3];
  reached.clear();
  const auto part = [&](double p0, double p1) {
    return [&, p0, p1](std::int64_t n, std::int64_t grain, double q0, double q1,
             const std::function<void(std::int64_t, std::int64_t)>& body) {
      return parallel(n, grain, p0 + (p1 - p0) * q0, p0 + (p1 - p0) * q1, body);
    };
  };
  if (!Reach(plan, whole, before, after, reach, rowAny, dims, changed, part(0.0, 0.8), scratch, stopAbove))
    return false;
  if (changed == 0 || (stopAbove >= 0 && changed > stopAbove))
    return true;
  // Gather in increasing order: count per row, then write at the rows' offsets.
  const std::int64_t nx = dims[0], rows = std::int64_t(dims[1]) * dims[2];
  std::vector<std::int64_t> localPerRow;
  std::vector<std::int64_t>& perRow = scratch ? scratch->perRow : localPerRow;
  perRow.resize(static_cast<std::size_t>(rows));
  if (!parallel(rows, 64, 0.8, 0.9, [&](std::int64_t r0, std::int64_t r1) {
        for (std::int64_t r = r0; r < r1; ++r)
        {
          std::int64_t count = 0;
          if (rowAny[r])
            for (std::int64_t v = r * nx; v < (r + 1) * nx; ++v)
              count += reach[v];
          perRow[r] = count;
        }
      }))
    return false;
  std::int64_t total = 0;
  for (std::int64_t& c : perRow)
  {
    const std::int64_t count = c;
    c = total; // the row's offset
    total += count;
  }
  Resize(reached, static_cast<std::size_t>(total));
  return parallel(rows, 64, 0.9, 1.0, [&](std::int64_t r0, std::int64_t r1) {
    for (std::int64_t r = r0; r < r1; ++r)
    {
      if (!rowAny[r])
        continue;
      std::int64_t* outList = reached.data() + perRow[r];
      for (std::int64_t v = r * nx; v < (r + 1) * nx; ++v)
        if (reach[v])
          *outList++ = v;
    }
  });
}

bool FootprintDiffers(const LAOPlan& plan, const int box[6], const float* a, const float* b,
  std::vector<std::uint8_t>& reach, const ContextualUpdate::ParallelFor& parallel)
{
  std::vector<std::uint8_t> rowAny;
  int dims[3];
  std::int64_t changed = 0;
  return Reach(plan, box, a, b, reach, rowAny, dims, changed, parallel);
}

bool UpdateLAOAfterOpacityEdit(const LAOPlan& plan, const float* before, const float* after,
  float* ao, const ContextualUpdate::ParallelFor& parallel, OpacityEditStats& stats,
  OpacityEditScratch* scratch)
{
  stats = OpacityEditStats();
  auto start = std::chrono::steady_clock::now();
  std::vector<std::int64_t> localReached;
  std::vector<std::int64_t>& reached = scratch ? scratch->reached : localReached;
  // The reach's own progress is the first tenth of the edit's.
  const ContextualUpdate::ParallelFor scaled =
    [&](std::int64_t n, std::int64_t grain, double p0, double p1,
      const std::function<void(std::int64_t, std::int64_t)>& body) {
      return parallel(n, grain, 0.1 * p0, 0.1 * p1, body);
    };
  // Reaching most of the volume, the march over whole rows costs less than
  // the list's runs (same values: a voxel's LAO does not depend on the run
  // it is marched in). The reach holds the changed voxels (the footprint
  // holds offset 0), so when those alone are that many, the dilation and
  // the list are skipped (an edit of almost every voxel cost 1.3 times a
  // full run with them: hydrogen.vti, 14 rays).
  const std::int64_t n = std::int64_t(plan.params.dims.x) * plan.params.dims.y * plan.params.dims.z;
  const std::int64_t most = n - n / 4;
  if (!OpacityEditReach(plan, before, after, reached, stats.changed, scaled, scratch, most))
    return false;
  stats.findMs = Since(start);
  const bool rows = stats.changed > most || static_cast<std::int64_t>(reached.size()) > most;
  stats.recomputed = rows ? n : static_cast<std::int64_t>(reached.size());
  start = std::chrono::steady_clock::now();
  const bool ok = stats.recomputed == 0 ||
    (rows ? parallel(n, 1024, 0.1, 1.0, [&](std::int64_t begin, std::int64_t end) {
      LAORange(plan, after, ao, begin, end);
    })
          : parallel(stats.recomputed, 4096, 0.1, 1.0, [&](std::int64_t begin, std::int64_t end) {
              LAOList(plan, after, ao, reached.data(), begin, end);
            }));
  stats.recomputeMs = Since(start);
  return ok;
}
}
