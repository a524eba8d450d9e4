#include "caoClassify.h"

#include <algorithm>
#include <cmath>

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

inline bool InLayers(
  const layout::ClipParams& p, const float* front, const float* back, const Projection& q)
{
  if (!q.inMap)
    return false;
  const std::size_t base = q.pixel * p.map.z;
  for (int l = 0; l < p.map.z; ++l)
  {
    const std::size_t i = base + l;
    if (front[i] <= q.depth && q.depth <= back[i])
      return true;
  }
  return false;
}

inline void FillOutside(const layout::ClipParams& p, const float* opacity, float* clipped,
  std::uint8_t* category, std::int64_t begin, std::int64_t end, CategoryCounts& counts)
{
  if (begin >= end)
    return;
  if (p.map.w == layout::CAO_MODE_SUBTRACT)
  {
    std::copy(opacity + begin, opacity + end, clipped + begin);
    std::fill(category + begin, category + end,
      static_cast<std::uint8_t>(layout::CAO_CATEGORY_UNAFFECTED));
    counts.unaffected += end - begin;
  }
  else
  {
    std::fill(clipped + begin, clipped + end, 0.0f);
    std::fill(
      category + begin, category + end, static_cast<std::uint8_t>(layout::CAO_CATEGORY_CLIPPED));
    counts.clipped += end - begin;
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

bool InsideClip(const layout::ClipParams& p, const float* front, const float* back, float x,
  float y, float z)
{
  return InLayers(p, front, back, Project(p, x, y, z));
}

void ClassifySlices(const layout::ClipParams& p, const int dims[3], const ClipMapsView& maps,
  const float* opacity, float* clipped, std::uint8_t* category, int zBegin, int zEnd,
  std::vector<std::int64_t>& affected, CategoryCounts& counts)
{
  const int whole[6] = { 0, dims[0] - 1, 0, dims[1] - 1, 0, dims[2] - 1 };
  ClassifyRegion(p, dims, maps, opacity, clipped, category, whole, zBegin, zEnd, affected, counts);
}

void ClassifyRegion(const layout::ClipParams& p, const int dims[3], const ClipMapsView& maps,
  const float* opacity, float* clipped, std::uint8_t* category, const int region[6], int zBegin,
  int zEnd, std::vector<std::int64_t>& affected, CategoryCounts& counts)
{
  const std::int64_t nx = dims[0], nxy = std::int64_t(dims[0]) * dims[1];
  const bool subtract = p.map.w == layout::CAO_MODE_SUBTRACT;
  const int bx0 = p.boxMin.x, bx1 = p.boxMax.x, by0 = p.boxMin.y, by1 = p.boxMax.y;
  const bool boxValid = p.boxMin.x <= p.boxMax.x && p.boxMin.y <= p.boxMax.y &&
    p.boxMin.z <= p.boxMax.z;
  const int rx0 = region[0], rx1 = region[1], ry0 = region[2], ry1 = region[3];
  const int cw = bx1 - bx0 + 2, ch = by1 - by0 + 2; // corner lattice of the box
  std::vector<std::uint8_t> lower, upper;
  if (boxValid)
  {
    lower.resize(static_cast<std::size_t>(cw) * ch);
    upper.resize(lower.size());
  }
  auto cornerPlane = [&](float zc, std::vector<std::uint8_t>& plane) {
    for (int cy = 0; cy < ch; ++cy)
      for (int cx = 0; cx < cw; ++cx)
        plane[static_cast<std::size_t>(cy) * cw + cx] = InsideClip(p, maps.front, maps.back,
          static_cast<float>(bx0 + cx) - 0.5f, static_cast<float>(by0 + cy) - 0.5f, zc);
  };
  // The region's voxels of rows [j0, j1] x columns [i0, i1] get the default.
  auto fillRows = [&](std::int64_t slice, int j0, int j1, int i0, int i1) {
    for (int j = j0; j <= j1 && i0 <= i1; ++j)
      FillOutside(p, opacity, clipped, category, slice + j * nx + i0, slice + j * nx + i1 + 1,
        counts);
  };
  bool haveLower = false;
  const float total = static_cast<float>(9 + p.aa.x);
  for (int k = std::max(zBegin, region[4]); k < std::min(zEnd, region[5] + 1); ++k)
  {
    const std::int64_t slice = k * nxy;
    if (!boxValid || k < p.boxMin.z || k > p.boxMax.z)
    {
      fillRows(slice, ry0, ry1, rx0, rx1);
      haveLower = false;
      continue;
    }
    if (!haveLower)
      cornerPlane(static_cast<float>(k) - 0.5f, lower);
    cornerPlane(static_cast<float>(k) + 0.5f, upper);
    haveLower = true;
    // The box lies inside the region: the region's rest is default.
    fillRows(slice, ry0, by0 - 1, rx0, rx1);
    for (int j = by0; j <= by1; ++j)
    {
      const std::int64_t row = slice + j * nx;
      FillOutside(p, opacity, clipped, category, row + rx0, row + bx0, counts);
      const std::size_t c0 = static_cast<std::size_t>(j - by0) * cw;
      const std::size_t c1 = c0 + cw;
      for (int i = bx0; i <= bx1; ++i)
      {
        const std::int64_t v = row + i;
        const std::size_t ci = static_cast<std::size_t>(i - bx0);
        const Projection centre =
          Project(p, static_cast<float>(i), static_cast<float>(j), static_cast<float>(k));
        int inside = InLayers(p, maps.front, maps.back, centre) + lower[c0 + ci] +
          lower[c0 + ci + 1] + lower[c1 + ci] + lower[c1 + ci + 1] + upper[c0 + ci] +
          upper[c0 + ci + 1] + upper[c1 + ci] + upper[c1 + ci + 1];
        float coverage;
        if (inside == 0)
          coverage = 0.0f;
        else if (inside == 9)
          coverage = 1.0f;
        else
        {
          for (int n = 0; n < p.aa.x; ++n)
          {
            const layout::vec4& o = p.aaOffsets[n];
            inside += InsideClip(p, maps.front, maps.back, static_cast<float>(i) + o.x,
              static_cast<float>(j) + o.y, static_cast<float>(k) + o.z);
          }
          coverage = static_cast<float>(inside) / total;
        }
        const bool candidate = InLayers(p, maps.candFront, maps.candBack, centre);
        std::uint8_t cat;
        if (subtract)
        {
          if (coverage == 1.0f)
          {
            cat = layout::CAO_CATEGORY_CLIPPED;
            clipped[v] = 0.0f;
          }
          else
          {
            cat = candidate ? layout::CAO_CATEGORY_AFFECTED : layout::CAO_CATEGORY_UNAFFECTED;
            clipped[v] = opacity[v] * (1.0f - coverage);
          }
        }
        else
        {
          if (coverage == 0.0f)
          {
            cat = layout::CAO_CATEGORY_CLIPPED;
            clipped[v] = 0.0f;
          }
          else
          {
            cat = candidate ? layout::CAO_CATEGORY_UNAFFECTED : layout::CAO_CATEGORY_AFFECTED;
            clipped[v] = opacity[v] * coverage;
          }
        }
        category[v] = cat;
        if (cat == layout::CAO_CATEGORY_CLIPPED)
          ++counts.clipped;
        else if (cat == layout::CAO_CATEGORY_AFFECTED)
        {
          ++counts.affected;
          affected.push_back(v);
        }
        else
          ++counts.unaffected;
      }
      FillOutside(p, opacity, clipped, category, row + bx1 + 1, row + rx1 + 1, counts);
    }
    fillRows(slice, by1 + 1, ry1, rx0, rx1);
    std::swap(lower, upper);
  }
}
}
