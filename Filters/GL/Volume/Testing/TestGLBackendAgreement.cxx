// The GL compute layer against the CPU kernels, on one context kind (argv:
// egl or osmesa), with no VTK:
//  - the GPU precompute equals the CPU LAO within 1e-5 (see below);
//  - at every pose of a sphere path (subtraction and probing; inside,
//    grazing, covering and leaving the volume) the GPU clip state (category
//    and coverage) equals the CPU classification voxel for voxel, and the
//    clipped opacity it implies equals the CPU's bit for bit;
//  - GPU CAO equals the GPU full recompute bit for bit (stored values) on
//    every voxel not in category a;
//  - GPU CAO is within 1e-5 of the CPU CAO.
// Tolerance: AO is stored on the GPU as 16-bit unorm, so one rounding of at
// most 0.5/65535 = 7.63e-6 separates it from the float value; the march
// itself runs the same operations in the same order (precise, no FMA), so a
// GPU whose division or summation rounds differently adds ~1e-7 at most.
#include "caoClassify.h"
#include "caoClipScene.h"
#include "caoGLTestUtilities.h"
#include "caoLAO.h"

#include <algorithm>

int TestGLBackendAgreement(int argc, char* argv[])
{
  auto context = caogltest::ContextOrSkip(caogltest::KindFromArgs(argc, argv));
  if (!context)
    return caogltest::Skip();
  const int dims[3] = { 40, 36, 32 };
  std::vector<std::uint8_t> scalars;
  std::vector<float> table, opacity;
  caogltest::MakeBlobVolume(dims, scalars, table, opacity);
  const std::size_t n = opacity.size();

  cao::VolumeGeometry geometry;
  std::copy(dims, dims + 3, geometry.dims);
  cao::LAOSettings settings = caotest::ExplicitSettings();
  settings.pattern = cao::RayPattern::Rays26;
  settings.reach = 4.0;
  cao::LAOPlan plan;
  std::string error;
  CAO_CHECK(cao::BuildLAOPlan(geometry, settings, plan, error), "%s", error.c_str());

  std::vector<float> pre(n);
  cao::LAORange(plan, opacity.data(), pre.data(), 0, static_cast<std::int64_t>(n));

  cao::gl::AOEngine engine(*context);
  cao::gl::VolumeUpload upload;
  std::copy(dims, dims + 3, upload.dims);
  upload.source = cao::gl::OpacitySource::Scalars8;
  upload.data = scalars.data();
  upload.opacityTable = table;
  CAO_CHECK(engine.SetVolume(upload, error), "%s", error.c_str());
  CAO_CHECK(engine.SetPlan(plan, error), "%s", error.c_str());
  CAO_CHECK(engine.Precompute(error), "%s", error.c_str());
  std::vector<std::uint16_t> gpuPre;
  CAO_CHECK(engine.ReadPrecomputedAO(gpuPre, error), "%s", error.c_str());
  double maxPre = 0.0;
  for (std::size_t v = 0; v < n; ++v)
    maxPre = std::max(maxPre, std::fabs(double(cao::gl::AOEngine::Dequantize(gpuPre[v])) - pre[v]));
  std::printf("precompute: max |GPU - CPU| = %.3g\n", maxPre);
  CAO_CHECK(maxPre <= 1e-5, "precompute differs by %g", maxPre);

  cao::ClipScene scene;
  CAO_CHECK(scene.BuildSphere(9.0, 0.75, 2, settings.reach, error), "%s", error.c_str());
  CAO_CHECK(engine.SetMaps(scene.camera.width, scene.camera.height, 2, scene.maps.front.data(),
              scene.maps.back.data(), scene.dilated.front.data(), scene.dilated.back.data(), error),
    "%s", error.c_str());
  const double path[][4] = { { 20, 18, 16, 0.0 }, { 10, 12, 8, 0.4 }, { 30, 25, 24, 1.1 },
    { -8, 18, 16, 0.2 }, { 20, 18, 40, 0.7 }, { 0.5, 0.5, 0.5, 2.0 }, { 39.5, 35.5, 31.5, 0.3 },
    { 100, 100, 100, 0.0 }, { 20, 18, 16, 3.0 } };
  int posesWithB = 0;
  for (int mode : { cao::layout::CAO_MODE_SUBTRACT, cao::layout::CAO_MODE_PROBE })
  {
    if (mode == cao::layout::CAO_MODE_PROBE)
      CAO_CHECK(engine.SetMaps(scene.camera.width, scene.camera.height, 2,
                  scene.maps.front.data(), scene.maps.back.data(), scene.eroded.front.data(),
                  scene.eroded.back.data(), error),
        "%s", error.c_str());
    const cao::ClipDepthMaps& cand = mode == cao::layout::CAO_MODE_SUBTRACT ? scene.dilated : scene.eroded;
    for (const auto& pose : path)
    {
      const cao::layout::ClipParams clip = scene.Pose(pose, pose[3], dims, mode, 16);
      // CPU reference.
      cao::ClipMapsView view{ scene.maps.front.data(), scene.maps.back.data(),
        cand.front.data(), cand.back.data() };
      std::vector<float> clipped(n);
      std::vector<std::uint8_t> category(n);
      std::vector<std::int64_t> affected;
      cao::CategoryCounts counts;
      cao::ClassifySlices(clip, dims, view, opacity.data(), clipped.data(), category.data(), 0,
        dims[2], affected, counts);
      std::vector<float> cpu(pre);
      cao::LAOList(plan, clipped.data(), cpu.data(), affected.data(), 0,
        static_cast<std::int64_t>(affected.size()));
      // GPU.
      cao::gl::UpdateStats stats;
      CAO_CHECK(engine.Update(clip, stats, error), "%s", error.c_str());
      std::vector<std::uint8_t> state;
      std::vector<std::uint16_t> gpu, full;
      CAO_CHECK(engine.ReadState(state, error), "%s", error.c_str());
      CAO_CHECK(engine.ReadCurrentAO(gpu, error), "%s", error.c_str());
      CAO_CHECK(engine.FullRecompute(full, error), "%s", error.c_str());
      CAO_CHECK(stats.affected == counts.affected && stats.clipped == counts.clipped &&
          stats.unaffected == counts.unaffected,
        "counts a/b/c GPU %lld/%lld/%lld CPU %lld/%lld/%lld", (long long)stats.clipped,
        (long long)stats.affected, (long long)stats.unaffected, (long long)counts.clipped,
        (long long)counts.affected, (long long)counts.unaffected);
      const int total = 9 + clip.aa.x;
      std::int64_t maskDiff = 0, opacityDiff = 0, exactDiff = 0;
      double maxDiff = 0.0;
      for (std::size_t v = 0; v < n; ++v)
      {
        const int cat = state[v] >> cao::layout::CAO_STATE_CATEGORY_SHIFT;
        const int count = state[v] & cao::layout::CAO_STATE_COUNT_MASK;
        maskDiff += cat != category[v];
        const float coverage = static_cast<float>(std::min(count, total)) / static_cast<float>(total);
        const float factor = mode == cao::layout::CAO_MODE_SUBTRACT ? 1.0f - coverage : coverage;
        opacityDiff += !(opacity[v] * factor == clipped[v]);
        if (cat != cao::layout::CAO_CATEGORY_CLIPPED)
        {
          exactDiff += full[v] != gpu[v];
          maxDiff = std::max(maxDiff, std::fabs(double(cao::gl::AOEngine::Dequantize(gpu[v])) - cpu[v]));
        }
      }
      posesWithB += counts.affected > 0;
      std::printf("mode %d pose (%g %g %g): a/b/c %lld/%lld/%lld region %lld, mask diff %lld, "
                  "opacity diff %lld, CAO vs full diff %lld, max |GPU-CPU| %.3g\n",
        mode, pose[0], pose[1], pose[2], (long long)counts.clipped, (long long)counts.affected,
        (long long)counts.unaffected, (long long)stats.regionVoxels, (long long)maskDiff,
        (long long)opacityDiff, (long long)exactDiff, maxDiff);
      CAO_CHECK(maskDiff == 0, "%lld voxels with another category", (long long)maskDiff);
      CAO_CHECK(opacityDiff == 0, "%lld voxels with another clipped opacity", (long long)opacityDiff);
      CAO_CHECK(exactDiff == 0, "GPU CAO differs from the GPU full recompute on %lld voxels",
        (long long)exactDiff);
      CAO_CHECK(maxDiff <= 1e-5, "GPU CAO differs from CPU CAO by %g", maxDiff);
    }
  }
  CAO_CHECK(posesWithB >= 8, "the path must exercise category b (%d poses did)", posesWithB);
  const auto& t = engine.Times();
  std::printf("GPU ms: precompute %.2f classify %.2f copy %.2f recompute %.2f full %.2f; "
              "resident %.2f B/voxel (volumes %.2f)\n",
    t.precompute, t.classify, t.copy, t.recompute, t.full,
    double(engine.ResidentBytes()) / double(n), double(engine.VolumeBytes()) / double(n));
  CAO_CHECK(engine.VolumeBytes() == 6 * static_cast<std::int64_t>(n), "volumes use %lld bytes",
    (long long)engine.VolumeBytes());

  // Interleaved variations (8 pattern variants picked by the parity of the
  // global voxel index, here with an odd origin) and a start offset: the
  // shader picks the CPU's variant for every voxel, and the contextual
  // update still equals the full recompute.
  for (cao::RayVariation variation : { cao::RayVariation::Rotate, cao::RayVariation::RotateJitter })
  {
    cao::VolumeGeometry odd = geometry;
    odd.origin[0] = 3;
    odd.origin[2] = 1;
    cao::LAOSettings varied = settings;
    varied.variation = variation;
    varied.startOffset = 0.5;
    cao::LAOPlan variedPlan;
    CAO_CHECK(cao::BuildLAOPlan(odd, varied, variedPlan, error), "%s", error.c_str());
    std::vector<float> cpu(n);
    cao::LAORange(variedPlan, opacity.data(), cpu.data(), 0, static_cast<std::int64_t>(n));
    CAO_CHECK(engine.ResetClip(error) && engine.SetPlan(variedPlan, error) &&
        engine.Precompute(error) && engine.ReadPrecomputedAO(gpuPre, error),
      "%s", error.c_str());
    double maxVaried = 0.0, maxChange = 0.0;
    for (std::size_t v = 0; v < n; ++v)
    {
      maxVaried = std::max(maxVaried, std::fabs(double(cao::gl::AOEngine::Dequantize(gpuPre[v])) - cpu[v]));
      maxChange = std::max(maxChange, std::fabs(double(cpu[v]) - pre[v]));
    }
    CAO_CHECK(engine.SetMaps(scene.camera.width, scene.camera.height, 2, scene.maps.front.data(),
                scene.maps.back.data(), scene.dilated.front.data(), scene.dilated.back.data(), error),
      "%s", error.c_str());
    const double pose[4] = { 20, 18, 16, 0.4 };
    cao::gl::UpdateStats stats;
    std::vector<std::uint16_t> gpu, full;
    CAO_CHECK(engine.Update(scene.Pose(pose, pose[3], dims, cao::layout::CAO_MODE_SUBTRACT, 16),
                stats, error) &&
        engine.ReadCurrentAO(gpu, error) && engine.FullRecompute(full, error),
      "%s", error.c_str());
    std::vector<std::uint8_t> state;
    CAO_CHECK(engine.ReadState(state, error), "%s", error.c_str());
    std::int64_t exactDiff = 0;
    for (std::size_t v = 0; v < n; ++v)
      if ((state[v] >> cao::layout::CAO_STATE_CATEGORY_SHIFT) != cao::layout::CAO_CATEGORY_CLIPPED)
        exactDiff += full[v] != gpu[v];
    std::printf("variation %s, offset 0.5: max |GPU - CPU| %.3g (vs no variation: %.3g), "
                "b %lld, CAO vs full diff %lld\n",
      cao::RayVariationName(variation), maxVaried, maxChange, (long long)stats.affected,
      (long long)exactDiff);
    CAO_CHECK(maxVaried <= 1e-5, "varied precompute differs by %g", maxVaried);
    CAO_CHECK(maxChange > 1e-3, "the variation changed nothing (%g)", maxChange);
    CAO_CHECK(stats.affected > 0 && exactDiff == 0, "CAO differs from the full recompute");
  }
  return 0;
}
