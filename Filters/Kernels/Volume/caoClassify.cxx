#include "caoClassify.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>

namespace cao
{
namespace
{
struct Projection
{
  bool inMap;
  std::size_t pixel; // y * width + x
  float depth;
};

inline Projection Project(const layout::ClipParams& p, float x, float y, float z)
{
  const layout::vec4* r = p.toCamera;
  const float u = ((r[0].x * x + r[0].y * y) + r[0].z * z) + r[0].w;
  const float v = ((r[1].x * x + r[1].y * y) + r[1].z * z) + r[1].w;
  const float d = ((r[2].x * x + r[2].y * y) + r[2].z * z) + r[2].w;
  Projection out{ false, 0, d };
  // Written so that NaN fails the test.
  if (u >= 0.0f && v >= 0.0f && u < static_cast<float>(p.map.x) &&
    v < static_cast<float>(p.map.y))
  {
    const int px = std::min(static_cast<int>(u), p.map.x - 1);
    const int py = std::min(static_cast<int>(v), p.map.y - 1);
    out.inMap = true;
    out.pixel = static_cast<std::size_t>(py) * p.map.x + px;
  }
  return out;
}

/// The centres of voxels x0 .. x0 + n - 1 of row (j, k): pixel[q] (-1 off
/// the map) and depth[q], the bits Project gives (the row's products formed
/// once, then the same float operations in the same order), computed
/// without branches.
inline void ProjectRun(const layout::ClipParams& p, int j, int k, int x0, int n,
  std::int64_t* __restrict pixel, float* __restrict depth)
{
  const layout::vec4* r = p.toCamera;
  const float y = static_cast<float>(j), z = static_cast<float>(k);
  // Locals, so that the stores cannot alias them.
  const float a0 = r[0].x, a1 = r[1].x, a2 = r[2].x;
  const float y0 = r[0].y * y, y1 = r[1].y * y, y2 = r[2].y * y;
  const float z0 = r[0].z * z, z1 = r[1].z * z, z2 = r[2].z * z;
  const float w0 = r[0].w, w1 = r[1].w, w2 = r[2].w;
  const float width = static_cast<float>(p.map.x), height = static_cast<float>(p.map.y);
  const int lastX = p.map.x - 1, lastY = p.map.y - 1;
  const std::int64_t mapX = p.map.x;
  for (int q = 0; q < n; ++q)
  {
    const float x = static_cast<float>(x0 + q);
    const float u = ((a0 * x + y0) + z0) + w0;
    const float v = ((a1 * x + y1) + z1) + w1;
    const float d = ((a2 * x + y2) + z2) + w2;
    const bool in = (u >= 0.0f) & (v >= 0.0f) & (u < width) & (v < height);
    // Off the map (NaN included) the conversion reads 0, never out of range.
    const int px = std::min(static_cast<int>(in ? u : 0.0f), lastX);
    const int py = std::min(static_cast<int>(in ? v : 0.0f), lastY);
    pixel[q] = in ? py * mapX + px : -1;
    depth[q] = d;
  }
}

/// One set of layer maps as the per-voxel tests read it: pixel `pixel`'s
/// layer l at front[pixel * pixelStride + l * layerStride] (and back[...]).
/// The raw maps are (layers, 1); ProofMaps' packed record interleaves the
/// four sets a voxel's centre reads, so that they share one cache line.
struct LayerSet
{
  const float* front = nullptr;
  const float* back = nullptr;
  std::size_t pixelStride = 0, layerStride = 1;
};

/// InSet of a point in pixel `pixel` (< 0: off the map) at `depth`.
inline bool InSetAt(const LayerSet& s, int layers, std::int64_t pixel, float depth)
{
  if (pixel < 0)
    return false;
  const std::size_t base = static_cast<std::size_t>(pixel) * s.pixelStride;
  if (layers == 2)
  {
    // Without branches: which of a pixel's intervals holds a voxel varies
    // from voxel to voxel, and mispredicted branches cost more than the
    // four loads.
    const std::size_t second = base + s.layerStride;
    const float f0 = s.front[base], b0 = s.back[base], f1 = s.front[second],
                b1 = s.back[second];
    return static_cast<bool>(((f0 <= depth) & (depth <= b0)) | ((f1 <= depth) & (depth <= b1)));
  }
  for (int l = 0; l < layers; ++l)
  {
    const std::size_t i = base + l * s.layerStride;
    if (s.front[i] <= depth && depth <= s.back[i])
      return true;
  }
  return false;
}

inline bool InSet(const LayerSet& s, int layers, const Projection& q)
{
  return q.inMap && InSetAt(s, layers, static_cast<std::int64_t>(q.pixel), q.depth);
}

inline void FillOutside(const layout::ClipParams& p, const float* opacity, float* clipped,
  std::uint8_t* category, std::int64_t begin, std::int64_t end, CategoryCounts& counts)
{
  if (begin >= end)
    return;
  FillUnclipped(p.map.w, opacity, clipped, category, begin, end);
  if (p.map.w == layout::CAO_MODE_SUBTRACT)
    counts.unaffected += end - begin;
  else
    counts.clipped += end - begin;
}

constexpr float PosInfinity = std::numeric_limits<float>::infinity();

/// Appends begin, begin + 1, ..., end - 1.
inline void AppendRange(std::vector<std::int64_t>& list, std::int64_t begin, std::int64_t end)
{
  const std::size_t at = list.size();
  list.resize(at + static_cast<std::size_t>(end - begin));
  std::iota(list.begin() + static_cast<std::ptrdiff_t>(at), list.end(), begin);
}

inline std::uint32_t Bits(float f)
{
  std::uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return u;
}
}

void FillUnclipped(int mode, const float* opacity, float* clipped, std::uint8_t* category,
  std::int64_t begin, std::int64_t end)
{
  if (begin >= end)
    return;
  if (mode == layout::CAO_MODE_SUBTRACT)
  {
    std::copy(opacity + begin, opacity + end, clipped + begin);
    std::fill(category + begin, category + end,
      static_cast<std::uint8_t>(layout::CAO_CATEGORY_UNAFFECTED));
  }
  else
  {
    std::fill(clipped + begin, clipped + end, 0.0f);
    std::fill(
      category + begin, category + end, static_cast<std::uint8_t>(layout::CAO_CATEGORY_CLIPPED));
  }
}

void BrickMemory::Allocate(const int dims[3], std::uint8_t value)
{
  std::size_t n = 1;
  for (int d = 0; d < 3; ++d)
  {
    this->bricks[d] = (dims[d] + BrickSize - 1) / BrickSize;
    n *= static_cast<std::size_t>(this->bricks[d]);
  }
  this->category.assign(n, value);
  this->opaque.assign(n, 0);
  this->differs.assign(n, 0);
}

void BrickMemory::FindOpaque(const int dims[3], const float* opacity, int zBegin, int zEnd)
{
  const std::int64_t nx = dims[0], nxy = std::int64_t(dims[0]) * dims[1];
  for (int bk = zBegin; bk < zEnd; ++bk)
  {
    std::uint8_t* layer = &this->opaque[this->Index(0, 0, bk)];
    std::fill(layer, layer + static_cast<std::size_t>(this->bricks[0]) * this->bricks[1], 0);
    for (int k = bk * BrickSize; k < std::min(dims[2], (bk + 1) * BrickSize); ++k)
      for (int j = 0; j < dims[1]; ++j)
      {
        const float* row = opacity + k * nxy + j * nx;
        std::uint8_t* flags = layer + static_cast<std::size_t>(j / BrickSize) * this->bricks[0];
        for (int i = 0; i < dims[0]; ++i)
          flags[i / BrickSize] |= Bits(row[i]) != 0u;
      }
  }
}

void SetAntiAliasingSamples(layout::ClipParams& params, int extraSamples)
{
  const int n = std::max(0, std::min(extraSamples, layout::CAO_MAX_AA_EXTRA_SAMPLES));
  params.aa = { n, 0, 0, 0 };
  // R3 sequence: alpha_d = 1 / phi3^d with phi3 the plastic-like constant.
  const double g = 1.22074408460575947536;
  const double a[3] = { 1.0 / g, 1.0 / (g * g), 1.0 / (g * g * g) };
  for (int i = 0; i < layout::CAO_MAX_AA_EXTRA_SAMPLES; ++i)
  {
    double c[3];
    for (int d = 0; d < 3; ++d)
    {
      const double t = 0.5 + a[d] * (i + 1);
      c[d] = (t - std::floor(t)) - 0.5;
    }
    params.aaOffsets[i] = { static_cast<float>(c[0]), static_cast<float>(c[1]),
      static_cast<float>(c[2]), 0.0f };
  }
}

bool CandidateBox(const double M[12], const double box[6], const int dims[3], int boxMin[3],
  int boxMax[3])
{
  // Invert the linear part (3x3, rows of M without the translation column).
  const double a = M[0], b = M[1], c = M[2], d = M[4], e = M[5], f = M[6], g = M[8], h = M[9],
               k = M[10];
  const double det = a * (e * k - f * h) - b * (d * k - f * g) + c * (d * h - e * g);
  if (!(std::fabs(det) > 0.0) || !std::isfinite(det))
    return false;
  const double inv[9] = { (e * k - f * h) / det, (c * h - b * k) / det, (b * f - c * e) / det,
    (f * g - d * k) / det, (a * k - c * g) / det, (c * d - a * f) / det, (d * h - e * g) / det,
    (b * g - a * h) / det, (a * e - b * d) / det };
  double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
  for (int corner = 0; corner < 8; ++corner)
  {
    const double cam[3] = { box[(corner & 1) ? 1 : 0] - M[3], box[(corner & 2) ? 3 : 2] - M[7],
      box[(corner & 4) ? 5 : 4] - M[11] };
    for (int r = 0; r < 3; ++r)
    {
      const double x = inv[3 * r] * cam[0] + inv[3 * r + 1] * cam[1] + inv[3 * r + 2] * cam[2];
      lo[r] = std::min(lo[r], x);
      hi[r] = std::max(hi[r], x);
    }
  }
  for (int r = 0; r < 3; ++r)
  {
    if (!std::isfinite(lo[r]) || !std::isfinite(hi[r]))
      return false;
    const double l = std::floor(lo[r]) - 1.0, u = std::ceil(hi[r]) + 1.0;
    if (u < 0.0 || l > dims[r] - 1)
      return false;
    boxMin[r] = static_cast<int>(std::max(0.0, l));
    boxMax[r] = static_cast<int>(std::min<double>(dims[r] - 1, u));
  }
  return true;
}

bool NarrowCandidateBox(const double M[12], const ClipMapsView& maps, int width, int height,
  int layers, int boxMin[3], int boxMax[3])
{
  if (width < 1 || height < 1 || layers < 1 || boxMin[0] > boxMax[0] || boxMin[1] > boxMax[1] ||
    boxMin[2] > boxMax[2])
    return false;
  const double a = M[0], b = M[1], c = M[2], d = M[4], e = M[5], f = M[6], g = M[8], h = M[9],
               k = M[10];
  const double det = a * (e * k - f * h) - b * (d * k - f * g) + c * (d * h - e * g);
  if (!(std::fabs(det) > 0.0) || !std::isfinite(det))
    return true; // CandidateBox refuses these; keep the box as it is
  const double inv[9] = { (e * k - f * h) / det, (c * h - b * k) / det, (b * f - c * e) / det,
    (f * g - d * k) / det, (a * k - c * g) / det, (c * d - a * f) / det, (d * h - e * g) / det,
    (b * g - a * h) / det, (a * e - b * d) / det };
  const float* fronts[2] = { maps.front, maps.candFront };
  const float* backs[2] = { maps.back, maps.candBack };
  double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
  double magnitude = 0.0; // of the camera coordinates met, for the rounding pad
  bool any = false;
  for (int py = 0; py < height; ++py)
    for (int px = 0; px < width; ++px)
    {
      // The pixel's intervals, both sets and every layer, as one depth range.
      float d0 = PosInfinity, d1 = -PosInfinity;
      const std::size_t base = (static_cast<std::size_t>(py) * width + px) * layers;
      for (int set = 0; set < 2; ++set)
        for (int l = 0; l < layers; ++l)
        {
          const float fr = fronts[set][base + l], bk = backs[set][base + l];
          if (fr <= bk) // NaN and empty intervals hold nothing
          {
            d0 = std::min(d0, fr);
            d1 = std::max(d1, bk);
          }
        }
      if (!(d0 <= d1))
        continue;
      const double q[3][2] = { { px - M[3], px + 1.0 - M[3] }, { py - M[7], py + 1.0 - M[7] },
        { d0 - M[11], d1 - M[11] } };
      if (!std::isfinite(q[2][0]) || !std::isfinite(q[2][1]))
        return true; // an unbounded interval: keep the box
      any = true;
      magnitude = std::max({ magnitude, std::fabs(double(px + 1)), std::fabs(double(py + 1)),
        std::fabs(double(d0)), std::fabs(double(d1)) });
      for (int r = 0; r < 3; ++r)
      {
        double mn = 0.0, mx = 0.0;
        for (int cc = 0; cc < 3; ++cc)
        {
          const double x0 = inv[3 * r + cc] * q[cc][0], x1 = inv[3 * r + cc] * q[cc][1];
          mn += std::min(x0, x1);
          mx += std::max(x0, x1);
        }
        lo[r] = std::min(lo[r], mn);
        hi[r] = std::max(hi[r], mx);
      }
    }
  if (!any)
  {
    boxMin[0] = boxMin[1] = boxMin[2] = 1;
    boxMax[0] = boxMax[1] = boxMax[2] = 0;
    return false;
  }
  for (int r = 0; r < 3; ++r)
  {
    // The point test evaluates the affine in float: a sample can land in a
    // pixel or depth range a few ulps of the coordinates' magnitudes away.
    const double rowNorm =
      std::fabs(inv[3 * r]) + std::fabs(inv[3 * r + 1]) + std::fabs(inv[3 * r + 2]);
    const double pad = 1e-5 * (magnitude + std::fabs(M[3]) + std::fabs(M[7]) + std::fabs(M[11])) * rowNorm;
    const double l = std::floor(lo[r] - pad) - 1.0, u = std::ceil(hi[r] + pad) + 1.0;
    if (!std::isfinite(l) || !std::isfinite(u))
      return true;
    boxMin[r] = std::max(boxMin[r], static_cast<int>(std::max<double>(l, boxMin[r])));
    boxMax[r] = std::min(boxMax[r], static_cast<int>(std::min<double>(u, boxMax[r])));
  }
  if (boxMin[0] > boxMax[0] || boxMin[1] > boxMax[1] || boxMin[2] > boxMax[2])
  {
    boxMin[0] = boxMin[1] = boxMin[2] = 1;
    boxMax[0] = boxMax[1] = boxMax[2] = 0;
    return false;
  }
  return true;
}

double ProofMaps::SampleReach(const layout::ClipParams& clip, const double pixelSize[2])
{
  const double scale[3] = { pixelSize[0], pixelSize[1], 1.0 };
  double reach = 0.0;
  for (int corner = 0; corner < 8; ++corner)
  {
    const double d[3] = { corner & 1 ? 0.5 : -0.5, corner & 2 ? 0.5 : -0.5,
      corner & 4 ? 0.5 : -0.5 };
    double sum = 0.0;
    for (int r = 0; r < 3; ++r)
    {
      const layout::vec4& m = clip.toCamera[r];
      const double c = scale[r] * (double(m.x) * d[0] + double(m.y) * d[1] + double(m.z) * d[2]);
      sum += c * c;
    }
    reach = std::max(reach, std::sqrt(sum));
  }
  return reach;
}

double ProofMaps::RoundingReach(
  const layout::ClipParams& clip, const double pixelSize[2], const int dims[3])
{
  // Project sums four float terms in float: each operation rounds by at
  // most 2^-24 of a partial sum, bounded by the terms' magnitudes at the
  // volume's far corner (samples lie within half a voxel of it).
  const double scale[3] = { pixelSize[0], pixelSize[1], 1.0 };
  double bound = 0.0;
  for (int r = 0; r < 3; ++r)
  {
    const layout::vec4& m = clip.toCamera[r];
    const double magnitude = std::fabs(double(m.x)) * (dims[0] + 0.5) +
      std::fabs(double(m.y)) * (dims[1] + 0.5) + std::fabs(double(m.z)) * (dims[2] + 0.5) +
      std::fabs(double(m.w));
    bound += scale[r] * 8.0 * std::ldexp(magnitude, -24);
  }
  return bound;
}

bool ProofMaps::Prepare(const layout::ClipParams& clip, const ClipMapsView& maps,
  std::uint64_t mapsVersion, const double pixelSize[2], const int dims[3], View& view)
{
  if (!pixelSize || !(pixelSize[0] > 0.0) || !(pixelSize[1] > 0.0) || !maps.front ||
    !maps.back || !maps.candFront || !maps.candBack || clip.map.x < 1 || clip.map.y < 1 ||
    clip.map.z < 1)
    return false;
  const double reach = SampleReach(clip, pixelSize);
  const double rounding = 2.0 * RoundingReach(clip, pixelSize, dims);
  const double needed = reach + rounding;
  if (!std::isfinite(needed) || !(needed > 0.0))
    return false;
  const float* layers[4] = { maps.front, maps.back, maps.candFront, maps.candBack };
  // The dilation's window grows with the radius in pixels: past
  // MaxProofPixels (a very anisotropic voxel against the pixel, sized by
  // the smallest spacing) the maps would cost more than they save.
  const double pixel = std::min(pixelSize[0], pixelSize[1]);
  if (1.1 * needed > MaxProofPixels * pixel)
    return false;
  const bool same = mapsVersion != 0 && mapsVersion == this->version &&
    std::equal(layers, layers + 4, this->of) && this->clip.width == clip.map.x &&
    this->clip.height == clip.map.y && this->clip.layers == clip.map.z;
  if (!same || needed > this->radius || needed < 0.67 * this->radius)
  {
    // 10% of headroom: a pose whose scale moves a little reuses them.
    const double grow = 1.1;
    this->radius = grow * needed;
    const std::size_t n = static_cast<std::size_t>(clip.map.x) * clip.map.y * clip.map.z;
    ClipDepthMaps* copies[2] = { &this->clip, &this->cand };
    for (int c = 0; c < 2; ++c)
    {
      copies[c]->Allocate(clip.map.x, clip.map.y, clip.map.z);
      std::copy(layers[2 * c], layers[2 * c] + n, copies[c]->front.begin());
      std::copy(layers[2 * c + 1], layers[2 * c + 1] + n, copies[c]->back.begin());
    }
    ClipCamera camera;
    camera.pixelSize[0] = pixelSize[0];
    camera.pixelSize[1] = pixelSize[1];
    camera.width = clip.map.x;
    camera.height = clip.map.y;
    camera.layers = clip.map.z;
    this->sample[0].Allocate(clip.map.x, clip.map.y, clip.map.z);
    this->sample[1].Allocate(clip.map.x, clip.map.y, clip.map.z);
    DilateErodeRows(this->clip, camera, this->radius, this->sample[0], this->sample[1], 0, clip.map.y);
    // The packed record: per pixel and layer, the clip, candidate, dilated
    // and eroded intervals side by side (8 floats; 64 bytes a pixel for two
    // layers), starting on a cache line.
    const std::size_t floats = 8 * n;
    this->packedStore.assign(floats + 16, 0.0f);
    float* packed = this->packedStore.data();
    while (reinterpret_cast<std::uintptr_t>(packed) % 64 != 0)
      ++packed;
    this->packedOffset = static_cast<std::size_t>(packed - this->packedStore.data());
    const ClipDepthMaps* sets[4] = { &this->clip, &this->cand, &this->sample[0], &this->sample[1] };
    for (std::size_t e = 0; e < n; ++e)
      for (int set = 0; set < 4; ++set)
      {
        packed[8 * e + 2 * set] = sets[set]->front[e];
        packed[8 * e + 2 * set + 1] = sets[set]->back[e];
      }
    this->version = mapsVersion;
    std::copy(layers, layers + 4, this->of);
    ++this->builds;
  }
  const auto viewOf = [](const ClipDepthMaps* m) {
    return m[0].front.empty() ? ClipMapsView{}
                              : ClipMapsView{ m[0].front.data(), m[0].back.data(),
                                  m[1].front.data(), m[1].back.data() };
  };
  view = { viewOf(this->sample), this->packedStore.data() + this->packedOffset };
  return true;
}

bool InsideClip(const layout::ClipParams& p, const float* front, const float* back, float x,
  float y, float z)
{
  const std::size_t layers = static_cast<std::size_t>(p.map.z);
  return InSet(LayerSet{ front, back, layers, 1 }, p.map.z, Project(p, x, y, z));
}

void ClassifySlices(const layout::ClipParams& p, const int dims[3], const ClipMapsView& maps,
  const float* opacity, float* clipped, std::uint8_t* category, int zBegin, int zEnd,
  std::vector<std::int64_t>& affected, CategoryCounts& counts)
{
  const int whole[6] = { 0, dims[0] - 1, 0, dims[1] - 1, 0, dims[2] - 1 };
  std::vector<std::vector<std::int64_t>> lists(static_cast<std::size_t>(std::max(0, zEnd - zBegin)));
  ClassifyRegion(p, dims, maps, opacity, clipped, category, whole, zBegin, zEnd, lists.data(), counts);
  for (const auto& l : lists)
    affected.insert(affected.end(), l.begin(), l.end());
}

namespace
{
constexpr float PosInf = std::numeric_limits<float>::infinity();

/// An interval as the point test reads it: empty when it contains nothing
/// (front > back, or NaN).
inline bool Usable(float f, float b)
{
  return f <= b;
}
}

void ClipMapsTiles::Build(const ClipMapsView& maps, int width, int height, int layers)
{
  this->Width = width;
  this->Height = height;
  this->Layers = layers;
  this->Levels.clear();
  if (width < 1 || height < 1 || layers < 1)
    return;
  const float* fronts[2] = { maps.front, maps.candFront };
  const float* backs[2] = { maps.back, maps.candBack };
  for (int tile = 4;; tile *= 4)
  {
    Level level;
    level.tile = tile;
    level.tilesX = (width + tile - 1) / tile;
    level.tilesY = (height + tile - 1) / tile;
    const std::size_t n = static_cast<std::size_t>(level.tilesX) * level.tilesY;
    for (int set = 0; set < 2; ++set)
    {
      level.minFront[set].assign(n, PosInf);
      level.maxBack[set].assign(n, -PosInf);
      level.maxFrontLayer[set].assign(n * layers, -PosInf);
      level.minBackLayer[set].assign(n * layers, PosInf);
    }
    if (this->Levels.empty())
    {
      // From the pixels.
      for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
        {
          const std::size_t t = static_cast<std::size_t>(y / tile) * level.tilesX + x / tile;
          const std::size_t base = (static_cast<std::size_t>(y) * width + x) * layers;
          for (int set = 0; set < 2; ++set)
            for (int l = 0; l < layers; ++l)
            {
              float f = fronts[set][base + l], b = backs[set][base + l];
              if (Usable(f, b))
              {
                level.minFront[set][t] = std::min(level.minFront[set][t], f);
                level.maxBack[set][t] = std::max(level.maxBack[set][t], b);
              }
              else
              {
                f = PosInf; // contains nothing: no range lies in it
                b = -PosInf;
              }
              float& mf = level.maxFrontLayer[set][t * layers + l];
              float& mb = level.minBackLayer[set][t * layers + l];
              mf = std::max(mf, f);
              mb = std::min(mb, b);
            }
        }
    }
    else
    {
      // From the level below: 4 x 4 of its tiles per tile.
      const Level& below = this->Levels.back();
      for (int ty = 0; ty < below.tilesY; ++ty)
        for (int tx = 0; tx < below.tilesX; ++tx)
        {
          const std::size_t c = static_cast<std::size_t>(ty) * below.tilesX + tx;
          const std::size_t t = static_cast<std::size_t>(ty / 4) * level.tilesX + tx / 4;
          for (int set = 0; set < 2; ++set)
          {
            level.minFront[set][t] = std::min(level.minFront[set][t], below.minFront[set][c]);
            level.maxBack[set][t] = std::max(level.maxBack[set][t], below.maxBack[set][c]);
            for (int l = 0; l < layers; ++l)
            {
              float& mf = level.maxFrontLayer[set][t * layers + l];
              float& mb = level.minBackLayer[set][t * layers + l];
              mf = std::max(mf, below.maxFrontLayer[set][c * layers + l]);
              mb = std::min(mb, below.minBackLayer[set][c * layers + l]);
            }
          }
        }
    }
    this->Levels.push_back(std::move(level));
    if (tile >= width && tile >= height)
      break;
  }
}

ClipMapsTiles::Coverage ClipMapsTiles::Query(int set, int px0, int px1, int py0, int py1,
  double d0, double d1, bool allInMap) const
{
  px0 = std::max(px0, 0);
  py0 = std::max(py0, 0);
  px1 = std::min(px1, this->Width - 1);
  py1 = std::min(py1, this->Height - 1);
  if (px0 > px1 || py0 > py1)
    return None;
  // The finest level whose tiles cover the rectangle with at most 6 x 6.
  const Level* level = &this->Levels.back();
  for (const Level& l : this->Levels)
    if (px1 / l.tile - px0 / l.tile < 6 && py1 / l.tile - py0 / l.tile < 6)
    {
      level = &l;
      break;
    }
  const int T = level->tile, L = this->Layers;
  bool none = true, all = allInMap;
  for (int ty = py0 / T; ty <= py1 / T && (none || all); ++ty)
    for (int tx = px0 / T; tx <= px1 / T && (none || all); ++tx)
    {
      const std::size_t t = static_cast<std::size_t>(ty) * level->tilesX + tx;
      // None: the range misses every interval of the tile.
      if (!(d1 < level->minFront[set][t] || d0 > level->maxBack[set][t]))
        none = false;
      // All: one layer holds the range at every pixel of the tile.
      bool held = false;
      for (int l = 0; l < L && !held; ++l)
        held = level->maxFrontLayer[set][t * L + l] <= d0 && d1 <= level->minBackLayer[set][t * L + l];
      if (!held)
        all = false;
    }
  return none ? None : (all ? All : Mixed);
}

namespace
{
/// The coverage of every point of the index-space box [lo, hi] (inclusive,
/// continuous) for map set `set`, proven with the tiles, or Mixed. The box
/// is projected in double and grown by a bound on the float evaluation
/// error of Project (operands and coordinates rounded to float: a few ulps
/// of the terms' magnitudes), so the float point test of any sample in it
/// falls in the queried pixels and depths.
ClipMapsTiles::Coverage BoxCoverage(const layout::ClipParams& p, const ClipMapsTiles& tiles,
  int set, const double lo[3], const double hi[3])
{
  double range[3][2];
  for (int r = 0; r < 3; ++r)
  {
    const layout::vec4& m = p.toCamera[r];
    const double c[3] = { m.x, m.y, m.z };
    double a = m.w, b = m.w, magnitude = std::fabs(static_cast<double>(m.w));
    for (int d = 0; d < 3; ++d)
    {
      const double x0 = c[d] * lo[d], x1 = c[d] * hi[d];
      a += std::min(x0, x1);
      b += std::max(x0, x1);
      magnitude += std::fabs(c[d]) * std::max(std::fabs(lo[d]), std::fabs(hi[d]));
    }
    const double pad = 1e-6 * magnitude + 1e-30;
    range[r][0] = a - pad;
    range[r][1] = b + pad;
    if (!std::isfinite(range[r][0]) || !std::isfinite(range[r][1]))
      return ClipMapsTiles::Mixed;
  }
  const double W = p.map.x, H = p.map.y;
  if (range[0][1] < 0.0 || range[0][0] >= W || range[1][1] < 0.0 || range[1][0] >= H)
    return ClipMapsTiles::None; // every sample off the map: in no layer
  const bool allInMap =
    range[0][0] >= 0.0 && range[0][1] < W && range[1][0] >= 0.0 && range[1][1] < H;
  const auto pixel = [](double v, double size) {
    return static_cast<int>(std::floor(std::min(std::max(v, -1.0), size)));
  };
  return tiles.Query(set, pixel(range[0][0], W), pixel(range[0][1], W), pixel(range[1][0], H),
    pixel(range[1][1], H), range[2][0], range[2][1], allInMap);
}

using BrickState = BrickCategory;

/// Set on a BrickMixed brick whose clip coverage is proven the same for
/// every voxel (none of the samples in the clip in subtraction, all of them
/// in probing: the opacity factor is 1); only the candidate test is mixed.
constexpr std::uint8_t BrickClipUniform = 0x40;

/// A brick's category from the coverage of its samples by the clip (None
/// or All: proven) and, asked only when it matters, of its centres by the
/// candidate layers (Mixed: BrickMixed | BrickClipUniform).
template <typename CandidateCoverage>
std::uint8_t BrickOf(
  const layout::ClipParams& p, ClipMapsTiles::Coverage clip, CandidateCoverage candidateCoverage)
{
  const bool subtract = p.map.w == layout::CAO_MODE_SUBTRACT;
  if (subtract && clip == ClipMapsTiles::All)
    return BrickClipped;
  if (!subtract && clip == ClipMapsTiles::None)
    return BrickClipped;
  const ClipMapsTiles::Coverage cand = candidateCoverage();
  if (cand == ClipMapsTiles::Mixed)
    return BrickMixed | BrickClipUniform;
  // Subtraction: not clipped; a candidate is affected. Probing: fully
  // inside; a candidate (deep inside) is unaffected.
  const bool candidate = cand == ClipMapsTiles::All;
  if (subtract)
    return candidate ? BrickAffected : BrickUnaffected;
  return candidate ? BrickUnaffected : BrickAffected;
}

/// The category every voxel of the brick [i0, i1] x [j0, j1] x [k0, k1]
/// provably gets, or BrickMixed (with BrickClipUniform when only the
/// candidate test is undecided). Clip samples lie within half a voxel of
/// the centres; the candidate test reads the centres only.
std::uint8_t ClassifyBrick(const layout::ClipParams& p, const ClipMapsTiles& tiles, int i0, int i1,
  int j0, int j1, int k0, int k1, bool clipUniformKnown = false)
{
  // clipUniformKnown: a block around the brick proved its clip coverage
  // uniform and unclipped (none of its samples in the clip in subtraction,
  // all of them in probing): only the candidate query is left.
  const double slo[3] = { i0 - 0.5, j0 - 0.5, k0 - 0.5 }, shi[3] = { i1 + 0.5, j1 + 0.5, k1 + 0.5 };
  const ClipMapsTiles::Coverage clip = clipUniformKnown
    ? (p.map.w == layout::CAO_MODE_SUBTRACT ? ClipMapsTiles::None : ClipMapsTiles::All)
    : BoxCoverage(p, tiles, 0, slo, shi);
  if (clip == ClipMapsTiles::Mixed)
    return BrickMixed;
  const double clo[3] = { double(i0), double(j0), double(k0) }, chi[3] = { double(i1), double(j1),
    double(k1) };
  return BrickOf(p, clip, [&] { return BoxCoverage(p, tiles, 1, clo, chi); });
}

/// The side, in bricks, of the blocks ClassifyRegion queries before their
/// bricks.
constexpr int BlockBricks = 4;

/// Set on a brick of the layer (with its category) when `memory` says its
/// voxels already hold that category: nothing to write.
constexpr std::uint8_t BrickUnchanged = 0x80;
}

void ClassifyRegion(const layout::ClipParams& p, const int dims[3], const ClipMapsView& maps,
  const float* opacity, float* clipped, std::uint8_t* category, const int region[6], int zBegin,
  int zEnd, std::vector<std::int64_t>* affectedBySlice, CategoryCounts& countsOut,
  const ClipMapsTiles* tiles, BrickMemory* memory, const ProofMaps::View* proof)
{
  // Counted in a local, added at the end (kept in registers).
  CategoryCounts counts;
  for (int k = zBegin; k < zEnd; ++k)
    affectedBySlice[k - zBegin].clear();
  std::vector<std::int64_t>* list = affectedBySlice; // the current slice's
  const std::int64_t nx = dims[0], nxy = std::int64_t(dims[0]) * dims[1];
  const bool subtract = p.map.w == layout::CAO_MODE_SUBTRACT;
  const int bx0 = p.boxMin.x, bx1 = p.boxMax.x, by0 = p.boxMin.y, by1 = p.boxMax.y;
  const int bz0 = p.boxMin.z, bz1 = p.boxMax.z;
  const bool boxValid = bx0 <= bx1 && by0 <= by1 && bz0 <= bz1;
  const int rx0 = region[0], rx1 = region[1], ry0 = region[2], ry1 = region[3];
  const int cw = bx1 - bx0 + 2, ch = by1 - by0 + 2; // corner lattice of the box
  if (tiles && !tiles->Built(p.map.x, p.map.y, p.map.z))
    tiles = nullptr;
  // The layer sets the voxels' tests read: the proof maps' packed record
  // when there is one (one cache line a pixel), the maps themselves if not.
  const int layers = p.map.z;
  const std::size_t pz = static_cast<std::size_t>(layers);
  LayerSet clipSet{ maps.front, maps.back, pz, 1 }, candSet{ maps.candFront, maps.candBack, pz, 1 };
  LayerSet dilatedSet, erodedSet;
  if (proof)
  {
    dilatedSet = { proof->sample.front, proof->sample.back, pz, 1 };
    erodedSet = { proof->sample.candFront, proof->sample.candBack, pz, 1 };
    if (proof->packed)
    {
      const float* r = proof->packed;
      clipSet = { r, r + 1, 8 * pz, 8 };
      candSet = { r + 2, r + 3, 8 * pz, 8 };
      dilatedSet = { r + 4, r + 5, 8 * pz, 8 };
      erodedSet = { r + 6, r + 7, 8 * pz, 8 };
    }
  }
  // The centres of a row's Mixed bricks, projected a run at a time.
  std::vector<std::int64_t> centrePixel(static_cast<std::size_t>(std::max(0, bx1 - bx0 + 1)));
  std::vector<float> centreDepth(centrePixel.size());
  std::vector<std::int64_t> runAffected(centrePixel.size()); // a run's b voxels
  std::vector<std::uint8_t> runDiffers(centrePixel.size());  // and which differ
  // Corner planes below and above the slice, filled as needed (2: not yet
  // evaluated), so that bricks decided at once cost no corner tests.
  constexpr std::uint8_t Unknown = 2;
  std::vector<std::uint8_t> lower, upper;
  // The brick layer's states, over the box's bricks.
  const int nbx = boxValid ? (bx1 - bx0) / BrickSize + 1 : 0;
  const int nby = boxValid ? (by1 - by0) / BrickSize + 1 : 0;
  std::vector<std::uint8_t> bricks;
  int brickLayer = -1, memoryLayer = -1;
  if (boxValid)
  {
    lower.assign(static_cast<std::size_t>(cw) * ch, Unknown);
    upper.assign(lower.size(), Unknown);
    bricks.assign(static_cast<std::size_t>(nbx) * nby, BrickMixed);
  }
  auto corner = [&](std::vector<std::uint8_t>& plane, std::size_t c, int cx, int cy, float zc) {
    std::uint8_t& v = plane[c];
    if (v == Unknown)
      v = InSet(clipSet, layers,
        Project(p, static_cast<float>(bx0 + cx) - 0.5f, static_cast<float>(by0 + cy) - 0.5f, zc));
    return static_cast<int>(v);
  };
  // The region's voxels of rows [j0, j1] x columns [i0, i1] get the default.
  auto fillRows = [&](std::int64_t slice, int j0, int j1, int i0, int i1) {
    for (int j = j0; j <= j1 && i0 <= i1; ++j)
      FillOutside(p, opacity, clipped, category, slice + j * nx + i0, slice + j * nx + i1 + 1,
        counts);
  };
  // Voxels [begin, end) of a brick decided at once.
  auto fillBrick = [&](BrickState state, std::int64_t begin, std::int64_t end) {
    std::vector<std::int64_t>& affected = *list;
    const std::int64_t n = end - begin;
    counts.byBrick += n;
    if (state == BrickClipped)
    {
      std::fill(clipped + begin, clipped + end, 0.0f);
      std::fill(category + begin, category + end,
        static_cast<std::uint8_t>(layout::CAO_CATEGORY_CLIPPED));
      counts.clipped += n;
      return;
    }
    // Coverage 0 (subtraction) or 1 (probing): the factor is exactly 1.
    std::copy(opacity + begin, opacity + end, clipped + begin);
    if (state == BrickAffected)
    {
      std::fill(category + begin, category + end,
        static_cast<std::uint8_t>(layout::CAO_CATEGORY_AFFECTED));
      AppendRange(affected, begin, end);
      counts.affected += n;
    }
    else
    {
      std::fill(category + begin, category + end,
        static_cast<std::uint8_t>(layout::CAO_CATEGORY_UNAFFECTED));
      counts.unaffected += n;
    }
  };
  bool haveLower = false;
  const float total = static_cast<float>(9 + p.aa.x);
  for (int k = std::max(zBegin, region[4]); k < std::min(zEnd, region[5] + 1); ++k)
  {
    const std::int64_t slice = k * nxy;
    list = affectedBySlice + (k - zBegin);
    std::vector<std::int64_t>& affected = *list;
    if (!boxValid || k < bz0 || k > bz1)
    {
      fillRows(slice, ry0, ry1, rx0, rx1);
      haveLower = false;
      continue;
    }
    if (!haveLower)
      std::fill(lower.begin(), lower.end(), Unknown);
    std::fill(upper.begin(), upper.end(), Unknown);
    haveLower = true;
    const float zLower = static_cast<float>(k) - 0.5f, zUpper = static_cast<float>(k) + 0.5f;
    if (tiles && (k - bz0) / BrickSize != brickLayer)
    {
      brickLayer = (k - bz0) / BrickSize;
      const int k0 = bz0 + brickLayer * BrickSize, k1 = std::min(bz1, k0 + BrickSize - 1);
      // Blocks of BlockBricks x BlockBricks bricks first: a block proven
      // uniform gives each of its bricks its category at once, and a block
      // whose clip coverage is proven uniform leaves its bricks only the
      // candidate query. (What a block proves holds for every voxel in it,
      // so the bricks get what their own queries would have proven, or
      // more; the voxels' results are the same either way.)
      for (int gy = 0; gy < nby; gy += BlockBricks)
        for (int gx = 0; gx < nbx; gx += BlockBricks)
        {
          const int gx1 = std::min(nbx, gx + BlockBricks), gy1 = std::min(nby, gy + BlockBricks);
          std::uint8_t block = BrickMixed;
          if (gx1 - gx > 1 || gy1 - gy > 1)
            block = ClassifyBrick(p, *tiles, bx0 + gx * BrickSize,
              std::min(bx1, bx0 + gx1 * BrickSize - 1), by0 + gy * BrickSize,
              std::min(by1, by0 + gy1 * BrickSize - 1), k0, k1);
          for (int by = gy; by < gy1; ++by)
            for (int bx = gx; bx < gx1; ++bx)
            {
              const int i0 = bx0 + bx * BrickSize, j0 = by0 + by * BrickSize;
              const int i1 = std::min(bx1, i0 + BrickSize - 1), j1 = std::min(by1, j0 + BrickSize - 1);
              const bool clipUniform = block == (BrickMixed | BrickClipUniform);
              std::uint8_t state = block == BrickMixed || clipUniform
                ? ClassifyBrick(p, *tiles, i0, i1, j0, j1, k0, k1, clipUniform)
                : block;
              if (memory)
              {
                std::uint8_t& held = memory->category[memory->Index(
                  i0 / BrickSize, j0 / BrickSize, k0 / BrickSize)];
                const std::uint8_t decided = state & ~BrickClipUniform;
                const bool same = decided != BrickMixed && held == decided;
                held = decided;
                if (same)
                  state |= BrickUnchanged;
              }
              bricks[static_cast<std::size_t>(by) * nbx + bx] = state;
            }
        }
    }
    if (memory && (k - bz0) / BrickSize != memoryLayer)
    {
      // A new layer of bricks: their Mixed flags are found below; without
      // tiles every brick is tested voxel by voxel.
      memoryLayer = (k - bz0) / BrickSize;
      for (int by = 0; by < nby; ++by)
        for (int bx = 0; bx < nbx; ++bx)
        {
          const std::size_t m = memory->Index((bx0 + bx * BrickSize) / BrickSize,
            (by0 + by * BrickSize) / BrickSize, k / BrickSize);
          memory->differs[m] = 0;
          if (!tiles)
            memory->category[m] = BrickMixed;
        }
    }
    // The box lies inside the region: the region's rest is default.
    fillRows(slice, ry0, by0 - 1, rx0, rx1);
    for (int j = by0; j <= by1; ++j)
    {
      const std::int64_t row = slice + j * nx;
      FillOutside(p, opacity, clipped, category, row + rx0, row + bx0, counts);
      const std::size_t c0 = static_cast<std::size_t>(j - by0) * cw;
      const std::size_t c1 = c0 + cw;
      const int cy0 = j - by0, cy1 = cy0 + 1;
      const std::uint8_t* brickRow = tiles ? &bricks[static_cast<std::size_t>(cy0 / BrickSize) * nbx] : nullptr;
      int projected = bx0 - 1; // the centres projected: [bx0, projected] at most
      int i = bx0;
      while (i <= bx1)
      {
        const int bx = (i - bx0) / BrickSize;
        int iEnd = std::min(bx1, bx0 + (bx + 1) * BrickSize - 1);
        const std::uint8_t held = brickRow ? brickRow[bx] : std::uint8_t(BrickMixed);
        if ((held & ~BrickUnchanged) != BrickMixed && (held & BrickClipUniform) == 0)
        {
          // A decided brick: the row's next bricks decided the same way
          // join it in one run (the same writes in fewer, longer calls).
          for (int next = bx + 1; next < nbx && brickRow[next] == held; ++next)
            iEnd = std::min(bx1, bx0 + (next + 1) * BrickSize - 1);
        }
        if (held & BrickUnchanged)
        {
          // Its voxels hold this category already: count, list, no writes.
          const std::int64_t n = iEnd + 1 - i;
          counts.byBrick += n;
          counts.unchanged += n;
          switch (held & ~BrickUnchanged)
          {
            case BrickClipped:
              counts.clipped += n;
              break;
            case BrickUnaffected:
              counts.unaffected += n;
              break;
            default:
              counts.affected += n;
              AppendRange(affected, row + i, row + iEnd + 1);
          }
          i = iEnd + 1;
          continue;
        }
        const BrickState state = static_cast<BrickState>(held & ~BrickClipUniform);
        const bool clipUniform = (held & BrickClipUniform) != 0;
        if (state != BrickMixed)
        {
          fillBrick(state, row + i, row + iEnd + 1);
          i = iEnd + 1;
          continue;
        }
        if (i > projected)
        {
          // Project the centres of this brick and of the row's next Mixed
          // bricks (either kind) at once.
          int runEnd = iEnd;
          for (int next = bx + 1; brickRow && next < nbx &&
               (brickRow[next] & ~BrickClipUniform) == BrickMixed;
               ++next)
            runEnd = std::min(bx1, bx0 + (next + 1) * BrickSize - 1);
          if (!brickRow)
            runEnd = bx1;
          ProjectRun(p, j, k, i, runEnd + 1 - i, centrePixel.data() + (i - bx0),
            centreDepth.data() + (i - bx0));
          projected = runEnd;
        }
        if (clipUniform)
        {
          // Every sample of these bricks (and of the row's next ones of the
          // same kind) proven out of the clip (subtraction) or in it
          // (probing): the factor is 1, no voxel is clipped, and the
          // candidate test alone decides b or c. Without branches (the
          // test's outcome flips along a row where the candidate layers'
          // surface crosses it); the b voxels are gathered, then appended.
          for (int next = bx + 1; next < nbx && brickRow[next] == held; ++next)
            iEnd = std::min(bx1, bx0 + (next + 1) * BrickSize - 1);
          const std::int64_t v0 = row + i, n = iEnd + 1 - i;
          std::copy(opacity + v0, opacity + v0 + n, clipped + v0);
          const std::int64_t* pix = centrePixel.data() + (i - bx0);
          const float* dep = centreDepth.data() + (i - bx0);
          const std::uint8_t inCand = static_cast<std::uint8_t>(
            subtract ? layout::CAO_CATEGORY_AFFECTED : layout::CAO_CATEGORY_UNAFFECTED);
          const std::uint8_t outCand = static_cast<std::uint8_t>(
            subtract ? layout::CAO_CATEGORY_UNAFFECTED : layout::CAO_CATEGORY_AFFECTED);
          std::int64_t* gathered = runAffected.data();
          std::int64_t nb = 0;
          for (std::int64_t q = 0; q < n; ++q)
          {
            const bool candidate = InSetAt(candSet, layers, pix[q], dep[q]);
            category[v0 + q] = candidate ? inCand : outCand;
            gathered[nb] = v0 + q;
            nb += (subtract == candidate);
          }
          affected.insert(affected.end(), gathered, gathered + nb);
          counts.affected += nb;
          counts.unaffected += n - nb;
          i = iEnd + 1;
          continue;
        }
        // The row's next bricks of the same kind join the run (without
        // tiles, the whole row: one Mixed run).
        for (int next = bx + 1; brickRow && next < nbx && brickRow[next] == held; ++next)
          iEnd = std::min(bx1, bx0 + (next + 1) * BrickSize - 1);
        if (!brickRow)
          iEnd = bx1;
        const int iBegin = i;
        const std::int64_t v0 = row + iBegin;
        std::int64_t* gathered = runAffected.data();
        std::uint8_t* differs = runDiffers.data();
        std::int64_t nb = 0, nClipped = 0;
        for (; i <= iEnd; ++i)
        {
          const std::int64_t v = row + i;
          const int cx = i - bx0;
          const std::size_t ci = static_cast<std::size_t>(cx);
          const std::int64_t pixel = centrePixel[ci];
          const float depth = centreDepth[ci];
          const bool candidate = InSetAt(candSet, layers, pixel, depth);
          float coverage;
          if (proof && pixel >= 0 && !InSetAt(dilatedSet, layers, pixel, depth))
          {
            // Outside the clip grown by the samples' reach: none is in it.
            coverage = 0.0f;
            ++counts.byCentre;
          }
          else if (proof && pixel >= 0 && InSetAt(erodedSet, layers, pixel, depth))
          {
            // Inside it shrunk by that reach: every sample is in it.
            coverage = 1.0f;
            ++counts.byCentre;
          }
          else
          {
            int inside = InSetAt(clipSet, layers, pixel, depth) +
              corner(lower, c0 + ci, cx, cy0, zLower) + corner(lower, c0 + ci + 1, cx + 1, cy0, zLower) +
              corner(lower, c1 + ci, cx, cy1, zLower) + corner(lower, c1 + ci + 1, cx + 1, cy1, zLower) +
              corner(upper, c0 + ci, cx, cy0, zUpper) + corner(upper, c0 + ci + 1, cx + 1, cy0, zUpper) +
              corner(upper, c1 + ci, cx, cy1, zUpper) + corner(upper, c1 + ci + 1, cx + 1, cy1, zUpper);
            if (inside == 0)
              coverage = 0.0f;
            else if (inside == 9)
              coverage = 1.0f;
            else if (opacity[v] == 0.0f)
            {
              // Transparent: its clipped opacity is 0 at any coverage, and
              // its category needs only that the coverage is neither 0 nor
              // 1, which the 9 samples that disagree already say: the
              // anti-aliasing samples would change no bit.
              coverage = static_cast<float>(inside) / total;
              ++counts.transparentShortcut;
            }
            else
            {
              for (int n = 0; n < p.aa.x; ++n)
              {
                const layout::vec4& o = p.aaOffsets[n];
                inside += InSet(clipSet, layers,
                  Project(p, static_cast<float>(i) + o.x, static_cast<float>(j) + o.y,
                    static_cast<float>(k) + o.z));
              }
              coverage = static_cast<float>(inside) / total;
            }
          }
          // From the coverage, without branches (the category flips where
          // the clip's and the candidate layers' surfaces cross the row):
          // a when fully clipped (coverage 1 subtracting, 0 probing, the
          // clipped opacity 0), else b or c by the candidate test with the
          // opacity times 1 - c (subtraction) or c (probing).
          const bool full = subtract ? coverage == 1.0f : coverage == 0.0f;
          const float factor = subtract ? 1.0f - coverage : coverage;
          const float value = full ? 0.0f : opacity[v] * factor;
          const bool isB = !full && candidate == subtract;
          clipped[v] = value;
          category[v] = static_cast<std::uint8_t>(full ? layout::CAO_CATEGORY_CLIPPED
              : (isB ? layout::CAO_CATEGORY_AFFECTED : layout::CAO_CATEGORY_UNAFFECTED));
          differs[i - iBegin] = Bits(value) != Bits(opacity[v]);
          gathered[nb] = v;
          nb += isB;
          nClipped += full;
        }
        const std::int64_t n = iEnd + 1 - iBegin;
        counts.clipped += nClipped;
        counts.affected += nb;
        counts.unaffected += n - nb - nClipped;
        affected.insert(affected.end(), gathered, gathered + nb);
        if (memory)
          for (int q = 0; q < n; ++q)
            if (differs[q])
              memory->differs[memory->Index((iBegin + q) / BrickSize, j / BrickSize, k / BrickSize)] = 1;
      }
      FillOutside(p, opacity, clipped, category, row + bx1 + 1, row + rx1 + 1, counts);
    }
    fillRows(slice, by1 + 1, ry1, rx0, rx1);
    std::swap(lower, upper);
  }
  countsOut.Add(counts);
}
}
