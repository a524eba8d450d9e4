// An edit of the opacity (a transfer-function change) recomputes only the
// voxels within the plan's footprint of a changed voxel, and the result
// equals a full recompute on the new opacity bit for bit: opacity raised
// from zero, lowered to zero, one narrow scalar bin, one local region
// (recomputing less than half of this small volume), the whole range, no
// change at all; with and without an interleaved ray variation, on an
// anisotropic grid whose origin is odd (the variants' parity), split over
// several work chunks as threads would. Negative control: recomputing only
// the changed voxels themselves (no footprint) must differ from the full
// recompute, so the comparison can fail.
#include "caoOpacityEdit.h"
#include "caoTestUtilities.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

namespace
{
/// Piecewise-linear opacity of a scalar in [0, 1] from (s, a) points.
float Map(const std::vector<double>& tf, double s)
{
  if (s <= tf[0])
    return static_cast<float>(tf[1]);
  for (std::size_t i = 2; i < tf.size(); i += 2)
    if (s <= tf[i])
    {
      const double t = (s - tf[i - 2]) / (tf[i] - tf[i - 2]);
      return static_cast<float>(tf[i - 1] + t * (tf[i + 1] - tf[i - 1]));
    }
  return static_cast<float>(tf.back());
}

std::int64_t Differing(const std::vector<float>& a, const std::vector<float>& b)
{
  std::int64_t n = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    n += std::memcmp(&a[i], &b[i], sizeof(float)) != 0;
  return n;
}
}

int TestOpacityEdit(int, char*[])
{
  cao::VolumeGeometry g;
  g.dims[0] = 37;
  g.dims[1] = 31;
  g.dims[2] = 29;
  g.origin[0] = 3; // odd: the variants' parity is the global index's
  g.origin[1] = 0;
  g.origin[2] = 1;
  g.spacing[0] = 1.0;
  g.spacing[1] = 1.3;
  g.spacing[2] = 0.8;
  const std::int64_t n = g.NumberOfVoxels();
  // A smooth field with blobs and a slab: every scalar value occurs.
  std::vector<double> scalar(static_cast<std::size_t>(n));
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i)
      {
        const double x = i / 36.0, y = j / 30.0, z = k / 28.0;
        double s = 0.5 + 0.25 * std::sin(7 * x + 3 * y) * std::cos(5 * z - 2 * x) +
          0.25 * std::exp(-40 * ((x - 0.6) * (x - 0.6) + (y - 0.4) * (y - 0.4) + (z - 0.5) * (z - 0.5)));
        scalar[i + std::size_t(g.dims[0]) * (j + std::size_t(g.dims[1]) * k)] = std::min(1.0, std::max(0.0, s));
      }
  struct Edit
  {
    const char* name;
    std::vector<double> from, to;
  };
  // The top 2% of the scalars: a local region (the blob's peak).
  std::vector<double> sorted = scalar;
  std::sort(sorted.begin(), sorted.end());
  const double peak = sorted[static_cast<std::size_t>(0.98 * (sorted.size() - 1))];
  const std::vector<Edit> edits = {
    { "raised from zero over the top quarter", { 0, 0, 0.3, 0, 0.6, 0.5, 0.75, 0.0, 1, 0 },
      { 0, 0, 0.3, 0, 0.6, 0.5, 0.75, 0.8, 1, 0.8 } },
    { "lowered to zero over the top quarter", { 0, 0, 0.3, 0, 0.6, 0.5, 0.75, 0.8, 1, 0.8 },
      { 0, 0, 0.3, 0, 0.6, 0.5, 0.75, 0.0, 1, 0 } },
    { "one narrow scalar bin", { 0, 0.2, 1, 0.2 }, { 0, 0.2, 0.5, 0.2, 0.505, 0.9, 0.51, 0.2, 1, 0.2 } },
    { "the top 2% of the scalars (a local region)", { 0, 0.2, 1, 0.2 }, { 0, 0.2, peak, 0.2, 1, 1 } },
    { "the whole range", { 0, 0.1, 1, 0.6 }, { 0, 0.3, 1, 0.2 } },
    { "no change", { 0, 0.1, 1, 0.6 }, { 0, 0.1, 1, 0.6 } },
  };
  const cao::ContextualUpdate::ParallelFor serial =
    [](std::int64_t count, std::int64_t, double, double,
      const std::function<void(std::int64_t, std::int64_t)>& body) {
      body(0, count);
      return true;
    };
  // Chunks of 7 in reverse order: a result that depended on the chunking
  // or order would show.
  const cao::ContextualUpdate::ParallelFor chunked =
    [](std::int64_t count, std::int64_t, double, double,
      const std::function<void(std::int64_t, std::int64_t)>& body) {
      for (std::int64_t end = count; end > 0; end -= 7)
        body(std::max<std::int64_t>(0, end - 7), end);
      return true;
    };
  for (int variation = 0; variation < 2; ++variation)
  {
    cao::LAOSettings s = caotest::ExplicitSettings();
    s.pattern = variation ? cao::RayPattern::Rays26 : cao::RayPattern::Rays14;
    s.reach = 4.5;
    s.variation = variation ? cao::RayVariation::RotateJitter : cao::RayVariation::None;
    cao::LAOPlan plan;
    std::string error;
    CAO_CHECK(cao::BuildLAOPlan(g, s, plan, error), "%s", error.c_str());
    int lo[3], hi[3];
    cao::OpacityFootprint(plan, lo, hi);
    std::printf("plan: %d rays, %d samples, %d variant(s); footprint x [%d, %d], y [%d, %d], z [%d, %d]\n",
      plan.rays, plan.samples, plan.variants, lo[0], hi[0], lo[1], hi[1], lo[2], hi[2]);
    CAO_CHECK(lo[0] < 0 && hi[0] > 0 && hi[1] < hi[0] + 1 && hi[2] > hi[0] - 1,
      "the footprint should follow the spacing (fewer voxels along y, more along z)");
    for (const Edit& e : edits)
    {
      std::vector<float> before(static_cast<std::size_t>(n)), after(before.size());
      for (std::int64_t v = 0; v < n; ++v)
      {
        before[v] = Map(e.from, scalar[v]);
        after[v] = Map(e.to, scalar[v]);
      }
      std::vector<float> full(before.size()), edited(before.size());
      cao::LAORange(plan, after.data(), full.data(), 0, n);
      cao::LAORange(plan, before.data(), edited.data(), 0, n);
      const std::vector<float> old = edited;
      std::vector<float> edited2 = edited;
      cao::OpacityEditStats stats, stats2;
      CAO_CHECK(cao::UpdateLAOAfterOpacityEdit(plan, before.data(), after.data(), edited.data(),
                  serial, stats), "aborted");
      CAO_CHECK(cao::UpdateLAOAfterOpacityEdit(plan, before.data(), after.data(), edited2.data(),
                  chunked, stats2), "aborted");
      const std::int64_t wrong = Differing(edited, full), wrong2 = Differing(edited2, full);
      const std::int64_t moved = Differing(old, full);
      std::printf("%-40s %s: %7lld changed, %7lld recomputed of %lld (%lld take a new value); "
                  "differing from the full recompute: %lld (chunked %lld)\n",
        e.name, variation ? "26 rays, rotate+jitter" : "14 rays", (long long)stats.changed,
        (long long)stats.recomputed, (long long)n, (long long)moved, (long long)wrong, (long long)wrong2);
      CAO_CHECK(wrong == 0 && wrong2 == 0, "%s: %lld / %lld voxels differ", e.name, (long long)wrong,
        (long long)wrong2);
      CAO_CHECK(stats.recomputed == stats2.recomputed && stats.changed == stats2.changed,
        "the chunking changed the counts");
      CAO_CHECK(stats.recomputed >= moved, "fewer recomputed than changed values");
      if (std::string(e.name) == "no change")
        CAO_CHECK(stats.changed == 0 && stats.recomputed == 0, "no change recomputed %lld",
          (long long)stats.recomputed);
      if (std::string(e.name).find("local") != std::string::npos)
        CAO_CHECK(stats.changed > 0 && stats.recomputed < n / 2, "a local edit recomputed %lld of %lld",
          (long long)stats.recomputed, (long long)n);
      // Negative control: the changed voxels alone, without the footprint.
      if (stats.changed > 0 && stats.changed < n)
      {
        std::vector<float> control = old;
        std::vector<std::int64_t> own;
        for (std::int64_t v = 0; v < n; ++v)
          if (std::memcmp(&before[v], &after[v], sizeof(float)) != 0)
            own.push_back(v);
        cao::LAOList(plan, after.data(), control.data(), own.data(), 0,
          static_cast<std::int64_t>(own.size()));
        const std::int64_t missed = Differing(control, full);
        std::printf("  control: the changed voxels alone leave %lld voxels differing\n",
          (long long)missed);
        CAO_CHECK(missed > 0, "negative control: recomputing only the changed voxels should miss some");
      }
    }
  }
  // The reach itself against a brute-force dilation by the footprint box,
  // on volumes thinner than the footprint along y or z (windows clipped at
  // both ends), with the changed voxels found by comparison and given as a
  // mask (`before` null, as vtkCAO::ComputeOpacity writes it in place).
  // Negative control: the brute force with the window one voxel narrower
  // along y or z differs.
  {
    cao::LAOSettings s = caotest::ExplicitSettings();
    s.reach = 4.5;
    int controlsDiffer = 0;
    for (const auto& d : std::vector<std::vector<int>>{ { 23, 5, 3 }, { 9, 17, 2 }, { 6, 4, 19 } })
    {
      cao::VolumeGeometry vg;
      std::copy(d.begin(), d.end(), vg.dims);
      vg.spacing[0] = vg.spacing[1] = vg.spacing[2] = 1.0;
      const std::int64_t vn = vg.NumberOfVoxels();
      cao::LAOPlan plan;
      std::string error;
      CAO_CHECK(cao::BuildLAOPlan(vg, s, plan, error), "%s", error.c_str());
      int lo[3], hi[3];
      cao::OpacityFootprint(plan, lo, hi);
      std::vector<float> a(static_cast<std::size_t>(vn), 0.25f), b = a;
      b[static_cast<std::size_t>(2 + vg.dims[0])] = 0.5f; // (2, 1, 0)
      b[static_cast<std::size_t>(vn - 1)] = -0.0f; // the last voxel
      const auto brute = [&](int narrowAxis) {
        std::vector<std::int64_t> out;
        const int nx = vg.dims[0], ny = vg.dims[1], nz = vg.dims[2];
        for (int k = 0; k < nz; ++k)
          for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i)
            {
              bool hit = false;
              for (int dz = lo[2]; dz <= hi[2] - (narrowAxis == 2) && !hit; ++dz)
                for (int dy = lo[1]; dy <= hi[1] - (narrowAxis == 1) && !hit; ++dy)
                  for (int dx = lo[0]; dx <= hi[0] && !hit; ++dx)
                  {
                    const int x = i + dx, y = j + dy, z = k + dz;
                    if (x < 0 || y < 0 || z < 0 || x >= nx || y >= ny || z >= nz)
                      continue;
                    const std::size_t w = x + std::size_t(nx) * (y + std::size_t(ny) * z);
                    hit = std::memcmp(&a[w], &b[w], sizeof(float)) != 0;
                  }
              if (hit)
                out.push_back(i + std::int64_t(nx) * (j + std::int64_t(ny) * k));
            }
        return out;
      };
      const std::vector<std::int64_t> want = brute(0);
      std::vector<std::int64_t> found, fromMask;
      std::int64_t changed = 0, changedMask = 0;
      cao::OpacityEditScratch scratch;
      CAO_CHECK(cao::OpacityEditReach(plan, a.data(), b.data(), found, changed, chunked, &scratch), "reach failed");
      std::uint8_t* mask = cao::PrepareEditMask(scratch, vn);
      for (std::int64_t v = 0; v < vn; ++v)
        mask[v] = std::memcmp(&a[v], &b[v], sizeof(float)) != 0;
      CAO_CHECK(cao::OpacityEditReach(plan, nullptr, b.data(), fromMask, changedMask, serial, &scratch),
        "reach from a mask failed");
      const std::int64_t narrowY = static_cast<std::int64_t>(brute(1).size()),
                         narrowZ = static_cast<std::int64_t>(brute(2).size());
      std::printf("reach on %d x %d x %d (footprint [%d, %d] x [%d, %d] x [%d, %d]): %lld voxels, brute force "
                  "%lld, from the mask %lld; controls, a voxel narrower along y: %lld, along z: %lld\n",
        d[0], d[1], d[2], lo[0], hi[0], lo[1], hi[1], lo[2], hi[2], (long long)found.size(),
        (long long)want.size(), (long long)fromMask.size(), (long long)narrowY, (long long)narrowZ);
      CAO_CHECK(found == want && fromMask == want && changed == changedMask,
        "the reach differs from a brute-force dilation");
      controlsDiffer += (narrowY != static_cast<std::int64_t>(want.size())) +
        (narrowZ != static_cast<std::int64_t>(want.size()));
    }
    CAO_CHECK(controlsDiffer >= 2, "negative control: a narrower window gave the same reach (%d differ)",
      controlsDiffer);
    // Without a mask in the scratch, `before` null is refused.
    cao::OpacityEditScratch empty;
    std::vector<std::int64_t> none;
    std::int64_t changed = 0;
    cao::LAOPlan plan;
    std::string error;
    CAO_CHECK(cao::BuildLAOPlan(g, s, plan, error), "%s", error.c_str());
    std::vector<float> b(static_cast<std::size_t>(n), 0.5f);
    CAO_CHECK(!cao::OpacityEditReach(plan, nullptr, b.data(), none, changed, serial, &empty),
      "a reach without `before` or a mask was not refused");
  }
  std::printf("PASSED\n");
  return 0;
}
