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
  for (auto& l : this->SliceLists)
    l.clear();
}

bool ContextualUpdate::Update(const Volume& volume, const layout::ClipParams& clip,
  const ClipMapsView& maps, std::uint64_t mapsVersion, const Buffers& out,
  const ParallelFor& parallel, Stats& stats, bool useTiles, const double* pixelSize)
{
  stats = Stats();
  const int* dims = volume.geometry.dims;
  const std::int64_t voxels = volume.geometry.NumberOfVoxels();
  const std::int64_t nx = dims[0], nxy = std::int64_t(dims[0]) * dims[1];
  const int mode = clip.map.w;
  const std::uint8_t unclipped = BrickMemory::Default(mode);
  // The candidate box grown to whole bricks: the bricks' memory describes
  // every voxel of a brick, and voxels outside the candidate box classify
  // as unclipped (CandidateBox is conservative), so growing it changes no
  // result.
  layout::ClipParams aligned = clip;
  int box[6] = { clip.boxMin.x, clip.boxMax.x, clip.boxMin.y, clip.boxMax.y, clip.boxMin.z,
    clip.boxMax.z };
  if (!Empty(box))
  {
    for (int d = 0; d < 3; ++d)
    {
      box[2 * d] = box[2 * d] / BrickSize * BrickSize;
      box[2 * d + 1] = std::min(dims[d] - 1, box[2 * d + 1] / BrickSize * BrickSize + BrickSize - 1);
    }
    aligned.boxMin = { box[0], box[2], box[4], 0 };
    aligned.boxMax = { box[1], box[3], box[5], 0 };
  }
  bool sameBricks = true;
  for (int d = 0; d < 3; ++d)
    sameBricks = sameBricks && this->Bricks.bricks[d] == (dims[d] + BrickSize - 1) / BrickSize;
  const bool incremental = this->Valid && mode == this->Mode && sameBricks &&
    static_cast<int>(this->SliceLists.size()) == dims[2];
  this->Valid = false; // until this pose is complete
  const auto fail = [this]() {
    this->Reset();
    return false;
  };

  // 1. Give the previous pose's marched voxels their precomputed AO back
  // (the first pose: every voxel). Nothing else differs from it.
  auto t0 = std::chrono::steady_clock::now();
  const float* pre = volume.precomputed;
  const std::uint16_t* pre16 = volume.precomputed16;
  float* ao = out.ao;
  std::uint16_t* ao16 = out.ao16;
  if (!ao == !ao16 || !pre == !pre16 || (pre16 && !ao16))
    return fail(); // exactly one AO buffer, one precomputed AO; a 16-bit one into 16 bits
  const auto restore = [ao, ao16, pre, pre16](std::int64_t v) {
    if (pre16)
      ao16[v] = pre16[v];
    else if (ao16)
      ao16[v] = QuantizeAO(pre[v]);
    else
      ao[v] = pre[v];
  };
  if (static_cast<int>(this->SliceLists.size()) != dims[2])
    this->SliceLists.assign(static_cast<std::size_t>(std::max(0, dims[2])), {});
  std::vector<std::int64_t>* lists = this->SliceLists.data();
  if (incremental)
  {
    // The marched voxels of slice k are lists[k] (the previous box's slices).
    const int z0 = Empty(this->Box) ? 0 : this->Box[4];
    const int n = Empty(this->Box) ? 0 : this->Box[5] - this->Box[4] + 1;
    std::int64_t restored = 0;
    std::mutex mutex;
    if (!parallel(n, 1, 0.0, 0.05, [&](std::int64_t b, std::int64_t e) {
          std::int64_t local = 0;
          for (std::int64_t s = b; s < e; ++s)
          {
            std::vector<std::int64_t>& list = lists[z0 + s];
            for (std::int64_t v : list)
              restore(v);
            local += static_cast<std::int64_t>(list.size());
            list.clear();
          }
          std::lock_guard<std::mutex> lock(mutex);
          restored += local;
        }))
      return fail();
    stats.restoredVoxels = restored;
  }
  else if (!parallel(voxels, 1 << 16, 0.0, 0.05, [&](std::int64_t b, std::int64_t e) {
             if (pre16)
               std::copy(pre16 + b, pre16 + e, ao16 + b);
             else if (ao16)
               std::transform(pre + b, pre + e, ao16 + b, QuantizeAO);
             else
               std::copy(pre + b, pre + e, ao + b);
           }))
    return fail();
  else
  {
    stats.restoredVoxels = voxels;
    for (auto& l : this->SliceLists)
      l.clear();
  }
  if (incremental)
    stats.copyMs = MillisecondsSince(t0);
  else
    stats.setupMs = MillisecondsSince(t0);

  // 2. Every voxel outside this pose's box holds the unclipped state: the
  // first pose writes it everywhere; later poses rewrite only the bricks of
  // the previous box, outside this one, that hold something else.
  t0 = std::chrono::steady_clock::now();
  BrickMemory& memory = this->Bricks;
  const int* nb = memory.bricks;
  const auto fillBrick = [&](int bi, int bj, int bk) {
    for (int k = bk * BrickSize; k < std::min(dims[2], (bk + 1) * BrickSize); ++k)
      for (int j = bj * BrickSize; j < std::min(dims[1], (bj + 1) * BrickSize); ++j)
      {
        const std::int64_t row = k * nxy + j * nx;
        FillUnclipped(mode, volume.opacity, out.clippedOpacity, out.category,
          row + bi * BrickSize, row + std::min<std::int64_t>(nx, (bi + 1) * BrickSize));
      }
  };
  if (!incremental)
  {
    memory.Allocate(dims, unclipped);
    if (!parallel(nb[2], 1, 0.05, 0.1, [&](std::int64_t b, std::int64_t e) {
          FillUnclipped(mode, volume.opacity, out.clippedOpacity, out.category,
            std::min(voxels, b * BrickSize * nxy), std::min(voxels, e * BrickSize * nxy));
          memory.FindOpaque(dims, volume.opacity, static_cast<int>(b), static_cast<int>(e));
        }))
      return fail();
    stats.classifiedVoxels = voxels;
    stats.setupMs += MillisecondsSince(t0);
    t0 = std::chrono::steady_clock::now();
  }
  else if (!Empty(this->Box))
  {
    const int* prev = this->Box; // brick-aligned
    std::int64_t reset = 0;
    std::mutex mutex;
    if (!parallel(prev[5] / BrickSize - prev[4] / BrickSize + 1, 1, 0.05, 0.1,
          [&](std::int64_t b, std::int64_t e) {
            std::int64_t local = 0;
            for (int bk = prev[4] / BrickSize + static_cast<int>(b);
                 bk < prev[4] / BrickSize + static_cast<int>(e); ++bk)
              for (int bj = prev[2] / BrickSize; bj <= prev[3] / BrickSize; ++bj)
                for (int bi = prev[0] / BrickSize; bi <= prev[1] / BrickSize; ++bi)
                {
                  const bool inBox = !Empty(box) && bi * BrickSize >= box[0] &&
                    bi * BrickSize <= box[1] && bj * BrickSize >= box[2] &&
                    bj * BrickSize <= box[3] && bk * BrickSize >= box[4] && bk * BrickSize <= box[5];
                  std::uint8_t& held = memory.category[memory.Index(bi, bj, bk)];
                  if (inBox || held == unclipped)
                    continue;
                  fillBrick(bi, bj, bk);
                  held = unclipped;
                  local += BrickSize * BrickSize * BrickSize;
                }
            std::lock_guard<std::mutex> lock(mutex);
            reset += local;
          }))
      return fail();
    stats.classifiedVoxels = reset; // at most: bricks at the volume's far faces are smaller
  }

  // 3. Classify this pose's box, brick layer by brick layer; the b lists
  // are concatenated in slice order, so the list is sorted whatever the
  // threads.
  const float* of[4] = { maps.front, maps.back, maps.candFront, maps.candBack };
  // The summaries of new maps (tiles, proof maps) are built once per maps,
  // as the maps are: setup, not this pose's work, when the maps have a
  // version; remade for another reason (no version, another radius), they
  // are the pose's.
  const bool newMaps = mapsVersion != 0 &&
    (mapsVersion != this->TilesVersion || !std::equal(of, of + 4, this->TilesOf));
  double mapsSetupMs = 0.0;
  auto tMaps = std::chrono::steady_clock::now();
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
  if (newMaps)
    mapsSetupMs += MillisecondsSince(tMaps);
  // (The proof maps remade for another reach on the same maps are the
  // pose's work: in classifyMs.)
  ProofMaps::View proofView;
  tMaps = std::chrono::steady_clock::now();
  const bool proofNewMaps = mapsVersion != 0 && mapsVersion != this->Proof.version;
  const ProofMaps::View* proof = useTiles && pixelSize &&
      this->Proof.Prepare(clip, maps, mapsVersion, pixelSize, dims, proofView)
    ? &proofView
    : nullptr;
  if (proofNewMaps)
    mapsSetupMs += MillisecondsSince(tMaps);
  const int slabs = Empty(box) ? 0 : box[5] - box[4] + 1;
  const int groups = (slabs + BrickSize - 1) / BrickSize;
  std::mutex mutex;
  CategoryCounts counts;
  if (!parallel(groups, 1, 0.1, 0.2, [&](std::int64_t b, std::int64_t e) {
        CategoryCounts local;
        const int zBegin = box[4] + static_cast<int>(b) * BrickSize;
        const int zEnd = std::min(box[4] + static_cast<int>(e) * BrickSize, box[5] + 1);
        ClassifyRegion(aligned, dims, maps, volume.opacity, out.clippedOpacity, out.category, box,
          zBegin, zEnd, lists + zBegin, local, tiles, &memory, proof);
        std::lock_guard<std::mutex> lock(mutex);
        counts.Add(local);
      }))
    return fail();
  if (incremental)
    stats.classifiedVoxels += Voxels(box) - counts.unchanged;
  // Outside the box every voxel holds the unclipped state.
  const std::int64_t outside = voxels - Voxels(box);
  if (mode == layout::CAO_MODE_SUBTRACT)
    counts.unaffected += outside;
  else
    counts.clipped += outside;
  stats.counts = counts;
  stats.classifyMs = MillisecondsSince(t0) - mapsSetupMs;
  stats.setupMs += mapsSetupMs;

  // 4. Narrow b by opacity: march only the b voxels whose footprint may
  // hold a voxel whose clipped opacity differs from its opacity, decided
  // per brick (BrickMemory::MayDiffer, dilated by the footprint in bricks).
  t0 = std::chrono::steady_clock::now();
  if (counts.affected > 0 && !this->NarrowByBricks(volume, box))
    return fail();
  for (int z = 0; z < slabs; ++z)
    stats.recomputedVoxels += static_cast<std::int64_t>(lists[box[4] + z].size());
  stats.narrowMs = MillisecondsSince(t0);

  // 5. Recompute them on the clipped opacity.
  t0 = std::chrono::steady_clock::now();
  if (!parallel(slabs, 1, 0.2, 1.0, [&](std::int64_t b, std::int64_t e) {
        for (std::int64_t z = b; z < e; ++z)
        {
          const std::vector<std::int64_t>& list = lists[box[4] + z];
          if (ao16)
            LAOList(*volume.plan, out.clippedOpacity, ao16, list.data(), 0,
              static_cast<std::int64_t>(list.size()));
          else
            LAOList(*volume.plan, out.clippedOpacity, ao, list.data(), 0,
              static_cast<std::int64_t>(list.size()));
        }
      }))
    return fail();
  stats.recomputeMs = MillisecondsSince(t0);

  std::copy(box, box + 6, this->Box);
  this->Mode = mode;
  this->Valid = true;
  return true;
}

bool ContextualUpdate::NarrowByBricks(const Volume& volume, const int box[6])
{
  const BrickMemory& memory = this->Bricks;
  const int* nb = memory.bricks;
  int lo[3], hi[3];
  OpacityFootprint(*volume.plan, lo, hi);
  // Brick B's voxels read voxels 4B + lo .. 4B + 3 + hi: bricks B + blo .. B + bhi.
  int blo[3], bhi[3], b0[3], b1[3], g0[3], g1[3], n[3];
  for (int d = 0; d < 3; ++d)
  {
    blo[d] = static_cast<int>(std::floor(lo[d] / double(BrickSize)));
    bhi[d] = static_cast<int>(std::floor((BrickSize - 1 + hi[d]) / double(BrickSize)));
    b0[d] = box[2 * d] / BrickSize;
    b1[d] = box[2 * d + 1] / BrickSize;
    g0[d] = std::max(0, b0[d] + blo[d]);
    g1[d] = std::min(nb[d] - 1, b1[d] + bhi[d]);
    n[d] = g1[d] - g0[d] + 1;
  }
  // The bricks that may differ over the grown region, then dilated along
  // x, y and z in turn (each pass over the region still needed).
  const std::size_t total = static_cast<std::size_t>(n[0]) * n[1] * n[2];
  std::vector<std::uint8_t>& a = this->Reach;
  std::vector<std::uint8_t>& b = this->ReachScratch;
  a.assign(total, 0);
  b.assign(total, 0);
  const auto at = [&](int i, int j, int k) {
    return static_cast<std::size_t>(i - g0[0]) +
      static_cast<std::size_t>(n[0]) * (static_cast<std::size_t>(j - g0[1]) + static_cast<std::size_t>(n[1]) * (k - g0[2]));
  };
  bool any = false;
  for (int k = g0[2]; k <= g1[2]; ++k)
    for (int j = g0[1]; j <= g1[1]; ++j)
      for (int i = g0[0]; i <= g1[0]; ++i)
        if (memory.MayDiffer(memory.Index(i, j, k)))
          a[at(i, j, k)] = 1, any = true;
  if (!any)
  {
    for (int z = box[4]; z <= box[5]; ++z)
      this->SliceLists[z].clear();
    return true;
  }
  const auto dilate = [&](int axis, const std::vector<std::uint8_t>& in, std::vector<std::uint8_t>& outFlags) {
    for (int k = g0[2]; k <= g1[2]; ++k)
      for (int j = g0[1]; j <= g1[1]; ++j)
        for (int i = g0[0]; i <= g1[0]; ++i)
        {
          int c[3] = { i, j, k };
          const int from = std::max(g0[axis], c[axis] + blo[axis]);
          const int to = std::min(g1[axis], c[axis] + bhi[axis]);
          std::uint8_t v = 0;
          for (int t = from; t <= to && !v; ++t)
          {
            c[axis] = t;
            v = in[at(c[0], c[1], c[2])];
          }
          outFlags[at(i, j, k)] = v;
        }
  };
  dilate(0, a, b);
  dilate(1, b, a);
  dilate(2, a, b);
  const int* dims = volume.geometry.dims;
  const std::int64_t nx = dims[0], nxy = std::int64_t(dims[0]) * dims[1];
  for (int z = box[4]; z <= box[5]; ++z)
  {
    // The slice's list is in increasing order: walk its rows along with it
    // (no division per voxel).
    std::vector<std::int64_t>& list = this->SliceLists[z];
    std::size_t kept = 0;
    int j = 0;
    std::int64_t rowStart = z * nxy;
    for (std::int64_t v : list)
    {
      while (v >= rowStart + nx)
      {
        rowStart += nx;
        ++j;
      }
      const int i = static_cast<int>(v - rowStart);
      if (b[at(i / BrickSize, j / BrickSize, z / BrickSize)])
        list[kept++] = v;
    }
    list.resize(kept);
  }
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
    const float f = full[static_cast<std::size_t>(v)];
    if (buffers.ao16)
    {
      // The stored values: the full recompute's, quantized as stored.
      const std::uint16_t q = buffers.ao16[v];
      if (std::isnan(f))
      {
        ++differing;
        maxDifference = 1.0;
      }
      else if (QuantizeAO(f) != q)
      {
        ++differing;
        const double d = std::fabs(static_cast<double>(DequantizeAO(QuantizeAO(f))) - DequantizeAO(q));
        maxDifference = std::max(maxDifference, d);
      }
      continue;
    }
    // Bitwise comparison: equal floats (and no NaN) or a difference.
    if (!(f == buffers.ao[v]))
    {
      ++differing;
      const double d = std::fabs(static_cast<double>(f) - buffers.ao[v]);
      maxDifference = std::max(maxDifference, std::isnan(d) ? 1.0 : d);
    }
  }
  return true;
}
}
