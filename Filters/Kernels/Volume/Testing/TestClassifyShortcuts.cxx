// The classification's shortcuts give the bits of testing every sample of
// every voxel (ClassifySlices: each voxel's category and clipped opacity,
// the b voxels' list in order, the counts), in subtraction and probing,
// for a sphere
// turned about the maps' view axis and moved through, across and out of a
// volume:
//  1. the candidate box narrowed to the depth maps' contents
//     (NarrowCandidateBox) against the box of the maps' camera-space bounds
//     (CandidateBox alone); it holds fewer voxels once the shape is turned.
//     Negative control: the narrowed box shrunk by a few voxels on every
//     side it does not share with the volume changes the classification
//     (the comparison sees a box that is too small, and the narrowed box is
//     within those few voxels of the least box that is right);
//  2. bricks decided by the tiles (blocks of bricks first), voxels decided
//     from their centre by the proof maps, runs of bricks whose clip is
//     proven uniform by the candidate test alone (ClassifyRegion with
//     ClipMapsTiles and ProofMaps, read through the packed record and
//     apart). Negative controls: the voxels
//     proven with the clip layers themselves (radius 0), and the packed
//     record with its dilated and eroded intervals swapped, change the
//     classification;
//  3. transparent voxels whose 9 samples disagree skip the anti-aliasing
//     samples, against an independent test of every sample (InsideClip).
//     Negative control: skipping them for opaque voxels too differs.
#include "caoClassify.h"
#include "caoClipScene.h"
#include "caoTestUtilities.h"

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

namespace
{
struct Result
{
  std::vector<float> clipped;
  std::vector<std::uint8_t> category;
  std::vector<std::int64_t> affected; ///< the b voxels as listed, in order
  cao::CategoryCounts counts;
};

Result Classify(const cao::layout::ClipParams& clip, const int dims[3],
  const cao::ClipMapsView& view, const std::vector<float>& opacity)
{
  Result r;
  r.clipped.assign(opacity.size(), -1.0f);
  r.category.assign(opacity.size(), 255);
  cao::ClassifySlices(clip, dims, view, opacity.data(), r.clipped.data(), r.category.data(), 0,
    dims[2], r.affected, r.counts);
  return r;
}

/// Voxels whose category or clipped opacity differ, plus the b voxels
/// listed by one and not the other (or out of order), plus the category
/// counts that differ.
std::int64_t Differences(const Result& a, const Result& b)
{
  std::int64_t n = 0;
  for (std::size_t v = 0; v < a.category.size(); ++v)
    n += a.category[v] != b.category[v] ||
      std::memcmp(&a.clipped[v], &b.clipped[v], sizeof(float)) != 0;
  std::size_t common = 0;
  while (common < a.affected.size() && common < b.affected.size() &&
    a.affected[common] == b.affected[common])
    ++common;
  n += static_cast<std::int64_t>(a.affected.size() + b.affected.size() - 2 * common);
  n += (a.counts.clipped != b.counts.clipped) + (a.counts.affected != b.counts.affected) +
    (a.counts.unaffected != b.counts.unaffected);
  return n;
}

/// The clip layers and the mode's candidate layers (dilated to subtract,
/// eroded to probe).
cao::ClipMapsView ViewFor(const cao::ClipScene& scene, int mode)
{
  const cao::ClipDepthMaps& cand =
    mode == cao::layout::CAO_MODE_SUBTRACT ? scene.dilated : scene.eroded;
  return { scene.maps.front.data(), scene.maps.back.data(), cand.front.data(), cand.back.data() };
}

std::int64_t BoxVoxels(const cao::layout::ClipParams& c)
{
  if (c.boxMin.x > c.boxMax.x || c.boxMin.y > c.boxMax.y || c.boxMin.z > c.boxMax.z)
    return 0;
  return std::int64_t(c.boxMax.x - c.boxMin.x + 1) * (c.boxMax.y - c.boxMin.y + 1) *
    (c.boxMax.z - c.boxMin.z + 1);
}
}

int TestClassifyShortcuts(int, char*[])
{
  const int dims[3] = { 48, 44, 40 };
  const std::size_t n = std::size_t(dims[0]) * dims[1] * dims[2];
  std::vector<float> opacity(n);
  for (std::size_t v = 0; v < n; ++v)
    opacity[v] = 0.05f + 0.9f * static_cast<float>((v * 2654435761u) % 1000) / 1000.0f;

  cao::ClipScene scene;
  std::string error;
  CAO_CHECK(scene.BuildSphere(10.0, 0.75, 2, 4.0, error), "%s", error.c_str());
  // Centre, angle about the view axis: inside, turned by 45 degrees, across
  // a face, at a corner, covering most of the volume, outside it.
  const double path[][4] = { { 24, 22, 20, 0.0 }, { 24, 22, 20, 0.785398 }, { 20, 18, 16, 0.4 },
    { -6, 22, 20, 0.9 }, { 47.5, 43.5, 39.5, 0.3 }, { 0.5, 0.5, 0.5, 2.0 }, { 100, 100, 100, 0.0 },
    { 30, 25, 12, 1.1 } };
  int tooSmallSeen = 0, narrower = 0;
  for (int mode : { cao::layout::CAO_MODE_SUBTRACT, cao::layout::CAO_MODE_PROBE })
  {
    const cao::ClipMapsView view = ViewFor(scene, mode);
    for (const auto& pose : path)
    {
      const cao::layout::ClipParams wide = scene.Pose(pose, pose[3], dims, mode, 16, false);
      const cao::layout::ClipParams tight = scene.Pose(pose, pose[3], dims, mode, 16, true);
      const Result a = Classify(wide, dims, view, opacity);
      const Result b = Classify(tight, dims, view, opacity);
      const std::int64_t diff = Differences(a, b);
      // The least shrink of the narrowed box that changes the result.
      int shrinkSeen = 0;
      if (BoxVoxels(tight) > 0)
        for (int shrink = 1; shrink <= 3 && !shrinkSeen; ++shrink)
        {
          cao::layout::ClipParams small = tight;
          int* lo[3] = { &small.boxMin.x, &small.boxMin.y, &small.boxMin.z };
          int* hi[3] = { &small.boxMax.x, &small.boxMax.y, &small.boxMax.z };
          for (int d = 0; d < 3; ++d)
          {
            if (*lo[d] > 0)
              *lo[d] += shrink;
            if (*hi[d] < dims[d] - 1)
              *hi[d] -= shrink;
          }
          if (Differences(a, Classify(small, dims, view, opacity)) > 0)
            shrinkSeen = shrink;
        }
      std::printf("mode %d pose (%g %g %g, %.2f rad): a/b/c %lld/%lld/%lld, box %lld -> %lld "
                  "voxels, %lld differ; the least shrink that differs: %d voxels (0: none up to 3)\n",
        mode, pose[0], pose[1], pose[2], pose[3], (long long)a.counts.clipped,
        (long long)a.counts.affected, (long long)a.counts.unaffected, (long long)BoxVoxels(wide),
        (long long)BoxVoxels(tight), (long long)diff, shrinkSeen);
      CAO_CHECK(diff == 0, "the narrowed box changes %lld voxels", (long long)diff);
      CAO_CHECK(BoxVoxels(tight) <= BoxVoxels(wide), "the narrowed box is larger");
      tooSmallSeen += shrinkSeen > 0;
      narrower += BoxVoxels(tight) < BoxVoxels(wide);
      if (pose[3] == 0.785398)
        CAO_CHECK(BoxVoxels(tight) * 10 <= BoxVoxels(wide) * 7,
          "turned by 45 degrees the box holds %lld of %lld voxels (at most 70%% expected)",
          (long long)BoxVoxels(tight), (long long)BoxVoxels(wide));
    }
  }
  // 2. Tiles and proof maps against every sample.
  std::int64_t byCentre = 0, byBrick = 0, wrongSwapped = 0, wrongVoxels = 0;
  for (int mode : { cao::layout::CAO_MODE_SUBTRACT, cao::layout::CAO_MODE_PROBE })
  {
    const cao::ClipMapsView view = ViewFor(scene, mode);
    cao::ClipMapsTiles tiles;
    tiles.Build(view, scene.camera.width, scene.camera.height, scene.camera.layers);
    cao::ProofMaps proof;
    for (const auto& pose : path)
    {
      const cao::layout::ClipParams clip = scene.Pose(pose, pose[3], dims, mode, 16);
      const Result every = Classify(clip, dims, view, opacity);
      cao::ProofMaps::View pv;
      CAO_CHECK(proof.Prepare(clip, view, 1 + mode, scene.camera.pixelSize, dims, pv),
        "no proof maps");
      CAO_CHECK(pv.packed != nullptr, "no packed record");
      cao::ProofMaps::View apart = pv, noRadius = pv, swapped = pv;
      apart.packed = nullptr;
      noRadius.packed = nullptr;
      noRadius.sample = { view.front, view.back, view.front, view.back };
      // The packed record with its dilated and eroded intervals swapped.
      const std::size_t records = static_cast<std::size_t>(scene.camera.width) *
        scene.camera.height * scene.camera.layers;
      std::vector<float> swappedRecord(pv.packed, pv.packed + 8 * records);
      for (std::size_t e = 0; e < records; ++e)
        for (int f = 0; f < 2; ++f)
          std::swap(swappedRecord[8 * e + 4 + f], swappedRecord[8 * e + 6 + f]);
      swapped.packed = swappedRecord.data();
      const int whole[6] = { 0, dims[0] - 1, 0, dims[1] - 1, 0, dims[2] - 1 };
      const auto shortcut = [&](const cao::ProofMaps::View* maps) {
        Result r;
        r.clipped.assign(n, -1.0f);
        r.category.assign(n, 255);
        std::vector<std::vector<std::int64_t>> lists(static_cast<std::size_t>(dims[2]));
        cao::ClassifyRegion(clip, dims, view, opacity.data(), r.clipped.data(),
          r.category.data(), whole, 0, dims[2], lists.data(), r.counts, &tiles, nullptr, maps);
        for (const auto& l : lists)
          r.affected.insert(r.affected.end(), l.begin(), l.end());
        return r;
      };
      const Result fast = shortcut(&pv);
      const std::int64_t diff = Differences(every, fast);
      const std::int64_t diffApart = Differences(every, shortcut(&apart));
      const std::int64_t swappedWrong = Differences(every, shortcut(&swapped));
      const std::int64_t voxelsWrong = Differences(every, shortcut(&noRadius));
      std::printf("mode %d pose (%g %g %g): by brick %lld, by centre %lld, %lld differ (%lld "
                  "read apart); controls: the record's intervals swapped %lld differ, voxels "
                  "with radius 0 %lld\n",
        mode, pose[0], pose[1], pose[2], (long long)fast.counts.byBrick,
        (long long)fast.counts.byCentre, (long long)diff, (long long)diffApart,
        (long long)swappedWrong, (long long)voxelsWrong);
      CAO_CHECK(diff == 0 && diffApart == 0, "the shortcuts change %lld voxels (%lld read apart)",
        (long long)diff, (long long)diffApart);
      byCentre += fast.counts.byCentre;
      byBrick += fast.counts.byBrick;
      wrongSwapped += swappedWrong;
      wrongVoxels += voxelsWrong;
    }
    CAO_CHECK(proof.builds == 1, "the proof maps were built %d times for one set of maps",
      proof.builds);
  }
  CAO_CHECK(byCentre > 0 && byBrick > 0, "shortcuts unused: by brick %lld, by centre %lld",
    (long long)byBrick, (long long)byCentre);
  CAO_CHECK(wrongSwapped > 0 && wrongVoxels > 0,
    "a swapped record and radius 0 gave the same bits (the comparison is blind): %lld and %lld differ",
    (long long)wrongSwapped, (long long)wrongVoxels);

  // 3. Transparent voxels skip their anti-aliasing samples: against an
  // independent classification that tests every sample with InsideClip
  // (the header's rules), on a volume where a third of the voxels are
  // transparent. Negative control: the same reference skipping the samples
  // of opaque voxels too differs.
  {
    std::vector<float> holes = opacity;
    for (std::size_t v = 0; v < n; ++v)
      if ((v * 2246822519u) % 3 == 0)
        holes[v] = 0.0f;
    std::int64_t skipped = 0, wrongWhenOpaqueSkip = 0;
    for (int mode : { cao::layout::CAO_MODE_SUBTRACT, cao::layout::CAO_MODE_PROBE })
    {
      const cao::ClipMapsView view = ViewFor(scene, mode);
      for (const auto& pose : path)
      {
        const cao::layout::ClipParams clip = scene.Pose(pose, pose[3], dims, mode, 16);
        const Result kernel = Classify(clip, dims, view, holes);
        const auto reference = [&](bool skipOpaqueToo) {
          Result r;
          r.clipped.assign(n, -1.0f);
          r.category.assign(n, 255);
          const bool subtract = mode == cao::layout::CAO_MODE_SUBTRACT;
          const float total = static_cast<float>(9 + clip.aa.x);
          for (int k = 0; k < dims[2]; ++k)
            for (int j = 0; j < dims[1]; ++j)
              for (int i = 0; i < dims[0]; ++i)
              {
                const std::size_t v = (std::size_t(k) * dims[1] + j) * dims[0] + i;
                const float x = static_cast<float>(i), y = static_cast<float>(j),
                            z = static_cast<float>(k);
                int inside = cao::InsideClip(clip, view.front, view.back, x, y, z);
                for (int c = 0; c < 8; ++c)
                  inside += cao::InsideClip(clip, view.front, view.back,
                    x + ((c & 1) ? 0.5f : -0.5f), y + ((c & 2) ? 0.5f : -0.5f),
                    z + ((c & 4) ? 0.5f : -0.5f));
                float coverage = inside == 0 ? 0.0f : inside == 9 ? 1.0f : -1.0f;
                if (coverage < 0.0f)
                {
                  if (!(holes[v] == 0.0f || skipOpaqueToo))
                    for (int a = 0; a < clip.aa.x; ++a)
                      inside += cao::InsideClip(clip, view.front, view.back,
                        x + clip.aaOffsets[a].x, y + clip.aaOffsets[a].y,
                        z + clip.aaOffsets[a].z);
                  coverage = static_cast<float>(inside) / total;
                }
                const bool candidate = cao::InsideClip(clip, view.candFront, view.candBack, x, y, z);
                if (subtract ? coverage == 1.0f : coverage == 0.0f)
                {
                  r.category[v] = cao::layout::CAO_CATEGORY_CLIPPED;
                  r.clipped[v] = 0.0f;
                  ++r.counts.clipped;
                  continue;
                }
                r.category[v] = (subtract == candidate) ? cao::layout::CAO_CATEGORY_AFFECTED
                                                        : cao::layout::CAO_CATEGORY_UNAFFECTED;
                r.clipped[v] = holes[v] * (subtract ? 1.0f - coverage : coverage);
                if (subtract == candidate)
                {
                  r.affected.push_back(static_cast<std::int64_t>(v));
                  ++r.counts.affected;
                }
                else
                  ++r.counts.unaffected;
              }
          return r;
        };
        const std::int64_t diff = Differences(kernel, reference(false));
        const std::int64_t control = Differences(kernel, reference(true));
        std::printf("mode %d pose (%g %g %g), a third transparent: %lld skipped the "
                    "anti-aliasing samples, %lld differ from every sample; control (opaque "
                    "voxels skipping them too): %lld differ\n",
          mode, pose[0], pose[1], pose[2], (long long)kernel.counts.transparentShortcut,
          (long long)diff, (long long)control);
        CAO_CHECK(diff == 0, "the transparent shortcut changes %lld voxels", (long long)diff);
        skipped += kernel.counts.transparentShortcut;
        wrongWhenOpaqueSkip += control;
      }
    }
    CAO_CHECK(skipped > 0, "no transparent voxel skipped its anti-aliasing samples");
    CAO_CHECK(wrongWhenOpaqueSkip > 0,
      "skipping the samples of opaque voxels too gave the same bits (the comparison is blind)");
  }

  // Every pose that reaches into the volume sees the too small box.
  CAO_CHECK(tooSmallSeen >= 12, "a box shrunk by up to 3 voxels changed %d poses", tooSmallSeen);
  CAO_CHECK(narrower >= 8, "the box narrowed at %d poses", narrower);
  return 0;
}
