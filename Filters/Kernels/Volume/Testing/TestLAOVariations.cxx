// Interleaved ray variations and the start offset: the vectorised run path
// (stride 2 per variant) equals the scalar path bit for bit; the variants
// really differ; a voxel's value depends on its global index, so a piece
// with an odd origin reproduces the whole volume; the offset moves the taps.
#include "caoLAO.h"
#include "caoTestUtilities.h"

#include <cmath>
#include <cstring>
#include <random>
#include <set>
#include <vector>

int TestLAOVariations(int, char*[])
{
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> uni(0.0f, 0.6f);
  cao::VolumeGeometry g;
  g.dims[0] = 21;
  g.dims[1] = 14;
  g.dims[2] = 12;
  g.spacing[0] = 1.0;
  g.spacing[1] = 0.8;
  g.spacing[2] = 1.3;
  std::vector<float> a(static_cast<std::size_t>(g.NumberOfVoxels()));
  for (float& v : a)
    v = uni(rng);

  const cao::RayVariation variations[] = { cao::RayVariation::None, cao::RayVariation::Rotate,
    cao::RayVariation::Jitter, cao::RayVariation::RotateJitter };
  std::vector<std::vector<float>> results;
  for (cao::RayVariation variation : variations)
  {
    for (double offset : { 0.0, 0.5 })
    {
      const bool jitter =
        variation == cao::RayVariation::Jitter || variation == cao::RayVariation::RotateJitter;
      if (jitter && offset != 0.0)
        continue; // jitter replaces the constant offset with its own
      cao::LAOSettings s = caotest::ExplicitSettings();
      s.pattern = cao::RayPattern::Rays14;
      s.reach = 4.5;
      s.variation = variation;
      s.startOffset = offset;
      cao::LAOPlan plan;
      std::string error;
      CAO_CHECK(cao::BuildLAOPlan(g, s, plan, error), "%s", error.c_str());
      const int V = cao::RayVariationCount(variation);
      CAO_CHECK(plan.variants == V && plan.params.rays.w == V, "variants %d", plan.variants);
      CAO_CHECK(plan.taps.size() == static_cast<std::size_t>(V) * 14 * (plan.samples - 1),
        "tap count %zu", plan.taps.size());
      // Whole volume through the run path, and through a list with gaps.
      std::vector<float> run(a.size(), -1.0f), list(a.size(), -1.0f);
      cao::LAORange(plan, a.data(), run.data(), 0, g.NumberOfVoxels());
      std::vector<std::int64_t> ids;
      for (std::int64_t v = 0; v < g.NumberOfVoxels(); ++v)
        if (v % 7 != 3)
          ids.push_back(v);
      cao::LAOList(plan, a.data(), list.data(), ids.data(), 0, static_cast<std::int64_t>(ids.size()));
      for (int k = 0; k < g.dims[2]; ++k)
        for (int j = 0; j < g.dims[1]; ++j)
          for (int i = 0; i < g.dims[0]; ++i)
          {
            const std::size_t v = i + g.dims[0] * (j + static_cast<std::size_t>(g.dims[1]) * k);
            const float scalar = cao::LAOVoxel(plan, a.data(), i, j, k);
            CAO_CHECK(std::memcmp(&scalar, &run[v], sizeof(float)) == 0,
              "variation %d offset %g voxel (%d,%d,%d): run %.9g scalar %.9g",
              static_cast<int>(variation), offset, i, j, k, run[v], scalar);
            if (v % 7 != 3)
              CAO_CHECK(std::memcmp(&scalar, &list[v], sizeof(float)) == 0, "list path differs");
            else
              CAO_CHECK(list[v] == -1.0f, "the list path wrote an unlisted voxel (a gap)");
            const double d = cao::LAOVoxelDouble(plan, a.data(), i, j, k);
            CAO_CHECK(std::abs(d - scalar) < 1e-6, "double march %.9g vs float %.9g", d, scalar);
          }
      results.push_back(run);

      // A piece with an odd origin, padded by the reach: its voxels away
      // from the piece's border equal the whole volume's.
      if (V == 8)
      {
        const int o[3] = { 3, 1, 5 }, n[3] = { 15, 11, 7 };
        cao::VolumeGeometry pg = g;
        std::vector<float> pa(static_cast<std::size_t>(n[0]) * n[1] * n[2]);
        for (int d = 0; d < 3; ++d)
        {
          pg.dims[d] = n[d];
          pg.origin[d] = o[d];
        }
        for (int k = 0; k < n[2]; ++k)
          for (int j = 0; j < n[1]; ++j)
            for (int i = 0; i < n[0]; ++i)
              pa[i + n[0] * (j + n[1] * k)] =
                a[(i + o[0]) + g.dims[0] * ((j + o[1]) + static_cast<std::size_t>(g.dims[1]) * (k + o[2]))];
        // Make the whole volume transparent outside the piece so that the
        // whole and the piece see the same medium everywhere.
        std::vector<float> masked(a.size(), 0.0f);
        for (int k = 0; k < n[2]; ++k)
          for (int j = 0; j < n[1]; ++j)
            for (int i = 0; i < n[0]; ++i)
            {
              const std::size_t v = (i + o[0]) + g.dims[0] * ((j + o[1]) + static_cast<std::size_t>(g.dims[1]) * (k + o[2]));
              masked[v] = a[v];
            }
        cao::LAOPlan piecePlan;
        CAO_CHECK(cao::BuildLAOPlan(pg, s, piecePlan, error), "%s", error.c_str());
        std::vector<float> whole(a.size()), piece(pa.size());
        cao::LAORange(plan, masked.data(), whole.data(), 0, g.NumberOfVoxels());
        cao::LAORange(piecePlan, pa.data(), piece.data(), 0, static_cast<std::int64_t>(pa.size()));
        for (int k = 0; k < n[2]; ++k)
          for (int j = 0; j < n[1]; ++j)
            for (int i = 0; i < n[0]; ++i)
            {
              const float w = whole[(i + o[0]) + g.dims[0] * ((j + o[1]) + static_cast<std::size_t>(g.dims[1]) * (k + o[2]))];
              const float p = piece[i + n[0] * (j + n[1] * k)];
              CAO_CHECK(std::memcmp(&w, &p, sizeof(float)) == 0,
                "piece voxel (%d,%d,%d): %.9g, whole %.9g", i, j, k, p, w);
            }
      }
    }
  }
  // Every (variation, offset) pair gives a different field.
  for (std::size_t x = 0; x < results.size(); ++x)
    for (std::size_t y = x + 1; y < results.size(); ++y)
      CAO_CHECK(results[x] != results[y], "configurations %zu and %zu give identical AO", x, y);

  // The start offset moves sample m to (m - offset) * step along the ray.
  {
    cao::VolumeGeometry line;
    line.dims[0] = line.dims[1] = line.dims[2] = 40;
    cao::LAOSettings s = caotest::ExplicitSettings();
    s.pattern = cao::RayPattern::Rays6;
    s.reach = 8.0;
    s.samples = 4;
    s.startOffset = 0.25;
    cao::LAOPlan plan;
    std::string error;
    CAO_CHECK(cao::BuildLAOPlan(line, s, plan, error), "%s", error.c_str());
    // Ray 0 is -x (AddAxes: axis 0, sign -1): taps at -(m - 0.25) * 2.
    for (int m = 1; m < 4; ++m)
    {
      const auto& t = plan.taps[m - 1];
      const double x = t.cell.x + t.frac.x;
      CAO_CHECK(std::abs(x + (m - 0.25) * 2.0) < 1e-6, "tap %d at %g", m, x);
    }
    // Jitter: variant v starts at (v + 0.5) / 8.
    s.variation = cao::RayVariation::Jitter;
    CAO_CHECK(cao::BuildLAOPlan(line, s, plan, error), "%s", error.c_str());
    for (int v = 0; v < 8; ++v)
    {
      const auto& t = plan.taps[static_cast<std::size_t>(v) * 6 * 3];
      const double x = t.cell.x + t.frac.x;
      CAO_CHECK(std::abs(x + (1.0 - (v + 0.5) / 8.0) * 2.0) < 1e-6, "variant %d first tap %g", v, x);
    }
    // Rotate: each variant is a rotation (unit length kept), all different.
    std::set<std::vector<double>> seen;
    for (int v = 0; v < 8; ++v)
    {
      double R[9];
      cao::VariationRotation(v, R);
      double det = R[0] * (R[4] * R[8] - R[5] * R[7]) - R[1] * (R[3] * R[8] - R[5] * R[6]) +
        R[2] * (R[3] * R[7] - R[4] * R[6]);
      CAO_CHECK(std::abs(det - 1.0) < 1e-12, "rotation %d has determinant %g", v, det);
      seen.insert(std::vector<double>(R, R + 9));
    }
    CAO_CHECK(seen.size() == 8, "the 8 rotations are not distinct");
    // Bad settings are errors.
    s.variation = cao::RayVariation::None;
    s.startOffset = 1.0;
    CAO_CHECK(!cao::BuildLAOPlan(line, s, plan, error), "offset 1 accepted");
    s.startOffset = 0.0;
    s.samples = 0;
    s.sampleDensity = 0.0;
    CAO_CHECK(!cao::BuildLAOPlan(line, s, plan, error), "density 0 accepted");
    s.sampleDensity = 0.5;
    CAO_CHECK(cao::BuildLAOPlan(line, s, plan, error) && plan.samples == 4,
      "density 0.5 over 8 voxels gave %d samples", plan.samples);
  }
  std::printf("variations: run == scalar == list bit for bit, pieces with odd origin exact\n");
  return 0;
}
