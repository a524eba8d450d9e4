#include "caoContextualUpdate.h"
#include "caoOpacityEdit.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>
#include <utility>

namespace cao
{
namespace
{
double MillisecondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
    .count();
}

bool Empty(const int box[6])
{
  return box[0] > box[1] || box[2] > box[3] || box[4] > box[5];
}

std::int64_t Voxels(const int box[6])
{
  return Empty(box) ? 0
                    : std::int64_t(box[1] - box[0] + 1) * (box[3] - box[2] + 1) *
      (box[5] - box[4] + 1);
}
}

void ContextualUpdate::Reset()
{
  this->Valid = false;
  this->Previous.clear();
  this->Current.clear();
}

bool ContextualUpdate::Update(const Volume& volume, const layout::ClipParams& clip,
  const ClipMapsView& maps, std::uint64_t mapsVersion, const Buffers& out,
  const ParallelFor& parallel, Stats& stats, bool useTiles)
{
  stats = Stats();
  const int* dims = volume.geometry.dims;
  const std::int64_t voxels = volume.geometry.NumberOfVoxels();
  const int mode = clip.map.w;
  const int box[6] = { clip.boxMin.x, clip.boxMax.x, clip.boxMin.y, clip.boxMax.y,
    clip.boxMin.z, clip.boxMax.z };
  const bool incremental = this->Valid && mode == this->Mode;
  this->Valid = false; // until this pose is complete

  // 1. Give the previous pose's b voxels their precomputed AO back (the
  // first pose: every voxel). Nothing else differs from it.
  auto t0 = std::chrono::steady_clock::now();
  const float* pre = volume.precomputed;
  float* ao = out.ao;
  bool ok;
  if (incremental)
  {
    const std::int64_t* list = this->Previous.data();
    ok = parallel(static_cast<std::int64_t>(this->Previous.size()), 4096, 0.0, 0.05,
      [&](std::int64_t b, std::int64_t e) {
        for (std::int64_t i = b; i < e; ++i)
          ao[list[i]] = pre[list[i]];
      });
    stats.restoredVoxels = static_cast<std::int64_t>(this->Previous.size());
  }
  else
  {
    ok = parallel(voxels, 1 << 16, 0.0, 0.05,
      [&](std::int64_t b, std::int64_t e) { std::copy(pre + b, pre + e, ao + b); });
    stats.restoredVoxels = voxels;
  }
  if (!ok)
  {
    this->Reset();
    return false;
  }
  stats.copyMs = MillisecondsSince(t0);

  // 2. Classify the union of this pose's candidate box and the previous
  // one's (everything, the first time), slab by slab; the b lists are
  // concatenated in slab order, so the list is sorted whatever the threads.
  t0 = std::chrono::steady_clock::now();
  int region[6] = { 0, dims[0] - 1, 0, dims[1] - 1, 0, dims[2] - 1 };
  if (incremental)
  {
    const int* prev = this->Box;
    for (int d = 0; d < 3; ++d)
    {
      region[2 * d] = std::min(Empty(box) ? dims[d] : box[2 * d], Empty(prev) ? dims[d] : prev[2 * d]);
      region[2 * d + 1] = std::max(Empty(box) ? -1 : box[2 * d + 1], Empty(prev) ? -1 : prev[2 * d + 1]);
    }
  }
  stats.classifiedVoxels = Voxels(region);
  const float* of[4] = { maps.front, maps.back, maps.candFront, maps.candBack };
  if (useTiles &&
    (mapsVersion == 0 || mapsVersion != this->TilesVersion ||
      !std::equal(of, of + 4, this->TilesOf) ||
      !this->Tiles.Built(clip.map.x, clip.map.y, clip.map.z)))
  {
    this->Tiles.Build(maps, clip.map.x, clip.map.y, clip.map.z);
    this->TilesVersion = mapsVersion;
    std::copy(of, of + 4, this->TilesOf);
  }
  const ClipMapsTiles* tiles = useTiles ? &this->Tiles : nullptr;
  // One list per slice, kept between poses (their memory is reused: no
  // fresh pages per pose), concatenated in slice order.
  // Work in groups of 4 slices aligned to the candidate box's brick layers
  // (ClassifyRegion decides a layer of 4^3 bricks once per call, and shares
  // corner planes between the slices of a call).
  const int layer = 4;
  const int boxZ = clip.boxMin.z <= clip.boxMax.z ? clip.boxMin.z : region[4];
  const int align = Empty(region) ? 0 : ((region[4] - boxZ) % layer + layer) % layer;
  const int z0 = region[4] - align;
  const int slabs = Empty(region) ? 0 : region[5] - z0 + 1;
  const int groups = (slabs + layer - 1) / layer;
  if (static_cast<int>(this->SliceLists.size()) < slabs)
    this->SliceLists.resize(static_cast<std::size_t>(slabs));
  std::mutex mutex;
  CategoryCounts counts;
  ok = parallel(groups, 1, 0.05, 0.2, [&](std::int64_t b, std::int64_t e) {
    CategoryCounts local;
    const int zBegin = z0 + static_cast<int>(b) * layer;
    const int zEnd = std::min(z0 + static_cast<int>(e) * layer, z0 + slabs);
    ClassifyRegion(clip, dims, maps, volume.opacity, out.clippedOpacity, out.category, region,
      zBegin, zEnd, this->SliceLists.data() + (zBegin - z0), local, tiles);
    std::lock_guard<std::mutex> lock(mutex);
    counts.Add(local);
  });
  if (!ok)
  {
    this->Reset();
    return false;
  }
  this->Current.clear();
  this->Current.reserve(static_cast<std::size_t>(counts.affected));
  for (int s = 0; s < slabs; ++s)
    this->Current.insert(
      this->Current.end(), this->SliceLists[s].begin(), this->SliceLists[s].end());
  // 2b. Narrow b by opacity: keep the b voxels whose footprint holds a
  // voxel whose clipped opacity differs from its opacity. Every such voxel
  // within reach of the region's b voxels lies in the region grown by the
  // footprint (outside the region the state is the unclipped one: equal
  // opacities in subtraction, and in probing the clipped voxels are
  // compared there too).
  stats.classifyMs = MillisecondsSince(t0);
  t0 = std::chrono::steady_clock::now();
  stats.recomputedVoxels = static_cast<std::int64_t>(this->Current.size());
  if (!this->Current.empty())
  {
    int lo[3], hi[3];
    OpacityFootprint(*volume.plan, lo, hi);
    int grown[6];
    for (int d = 0; d < 3; ++d)
    {
      grown[2 * d] = std::max(0, region[2 * d] + lo[d]);
      grown[2 * d + 1] = std::min(dims[d] - 1, region[2 * d + 1] + hi[d]);
    }
    std::vector<std::uint8_t>& reach = this->Reach;
    if (!FootprintDiffers(*volume.plan, grown, volume.opacity, out.clippedOpacity, reach,
          [&](std::int64_t n, std::int64_t grain, double p0, double p1,
            const std::function<void(std::int64_t, std::int64_t)>& body) {
            return parallel(n, grain, 0.2 + 0.05 * p0, 0.2 + 0.05 * p1, body);
          }))
    {
      this->Reset();
      return false;
    }
    const std::int64_t gx = grown[1] - grown[0] + 1, gy = grown[3] - grown[2] + 1;
    const std::int64_t nx = dims[0], nxy = std::int64_t(dims[0]) * dims[1];
    std::size_t kept = 0;
    for (std::int64_t v : this->Current)
    {
      const std::int64_t k = v / nxy, j = (v - k * nxy) / nx, i = v - k * nxy - j * nx;
      if (reach[static_cast<std::size_t>((i - grown[0]) + gx * ((j - grown[2]) + gy * (k - grown[4])))])
        this->Current[kept++] = v;
    }
    this->Current.resize(kept);
    stats.recomputedVoxels = static_cast<std::int64_t>(kept);
  }
  stats.narrowMs = MillisecondsSince(t0);
  // Outside the region every voxel holds the unclipped state.
  const std::int64_t outside = voxels - stats.classifiedVoxels;
  if (mode == layout::CAO_MODE_SUBTRACT)
    counts.unaffected += outside;
  else
    counts.clipped += outside;
  stats.counts = counts;

  // 3. Recompute the b voxels on the clipped opacity.
  t0 = std::chrono::steady_clock::now();
  const std::int64_t* list = this->Current.data();
  ok = parallel(static_cast<std::int64_t>(this->Current.size()), 256, 0.2, 1.0,
    [&](std::int64_t b, std::int64_t e) {
      LAOList(*volume.plan, out.clippedOpacity, ao, list, b, e);
    });
  if (!ok)
  {
    this->Reset();
    return false;
  }
  stats.recomputeMs = MillisecondsSince(t0);

  std::copy(box, box + 6, this->Box);
  this->Mode = mode;
  std::swap(this->Previous, this->Current); // Affected() reports this pose's list
  this->Valid = true;
  return true;
}

bool ContextualUpdate::Verify(const Volume& volume, const Buffers& buffers,
  const ParallelFor& parallel, std::int64_t& differing, double& maxDifference, double& ms)
{
  const auto t0 = std::chrono::steady_clock::now();
  const std::int64_t voxels = volume.geometry.NumberOfVoxels();
  std::vector<float> full(static_cast<std::size_t>(voxels));
  if (!parallel(voxels, 1024, 0.0, 1.0, [&](std::int64_t b, std::int64_t e) {
        LAORange(*volume.plan, buffers.clippedOpacity, full.data(), b, e);
      }))
    return false;
  ms = MillisecondsSince(t0);
  differing = 0;
  maxDifference = 0.0;
  for (std::int64_t v = 0; v < voxels; ++v)
  {
    if (buffers.category[v] == layout::CAO_CATEGORY_CLIPPED)
      continue;
    // Bitwise comparison: equal floats (and no NaN) or a difference.
    if (!(full[static_cast<std::size_t>(v)] == buffers.ao[v]))
    {
      ++differing;
      const double d = std::fabs(static_cast<double>(full[static_cast<std::size_t>(v)]) - buffers.ao[v]);
      maxDifference = std::max(maxDifference, std::isnan(d) ? 1.0 : d);
    }
  }
  return true;
}
}
