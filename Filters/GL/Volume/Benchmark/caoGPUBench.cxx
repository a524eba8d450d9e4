// cao-gpu-bench: the GL compute layer's benchmark, with no VTK or ParaView.
// It needs libEGL (or libOSMesa) at run time and GLM at build time.
//
//   cao-gpu-bench VOLUME.raw NX NY NZ [--rays 6,14,26,54] [--poses N]
//                 [--upsample K] [--context auto|egl|osmesa] [--reach R]
//
// VOLUME.raw: 8-bit scalars, x fastest. --upsample K resamples it
// trilinearly to K times the size per axis (embryo 256^3 -> 512^3, the
// paper's Skeleton size). For each ray set it runs the full LAO precompute
// and a clip sphere (radius: a quarter of the smallest extent) moving along
// the volume diagonal, and prints, side by side, the full LAO time, the mean
// CAO update time (classification + copy + recompute) and their ratio, all
// GPU milliseconds from timer queries, plus the bytes per voxel resident.
#include "caoAOEngine.h"
#include "caoClipScene.h"
#include "caoGLContext.h"
#include "caoLAO.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace
{
int Fail(const std::string& message)
{
  std::fprintf(stderr, "cao-gpu-bench: error: %s\n", message.c_str());
  return 2;
}

std::vector<std::uint8_t> Upsample(const std::vector<std::uint8_t>& in, const int d[3], int k, int out[3])
{
  for (int a = 0; a < 3; ++a)
    out[a] = d[a] * k;
  std::vector<std::uint8_t> r(static_cast<std::size_t>(out[0]) * out[1] * out[2]);
  auto at = [&](int x, int y, int z) {
    x = std::min(std::max(x, 0), d[0] - 1);
    y = std::min(std::max(y, 0), d[1] - 1);
    z = std::min(std::max(z, 0), d[2] - 1);
    return float(in[(static_cast<std::size_t>(z) * d[1] + y) * d[0] + x]);
  };
  std::size_t v = 0;
  for (int z = 0; z < out[2]; ++z)
    for (int y = 0; y < out[1]; ++y)
      for (int x = 0; x < out[0]; ++x, ++v)
      {
        const glm::vec3 p = (glm::vec3(x, y, z) + 0.5f) / float(k) - 0.5f;
        const glm::ivec3 i = glm::ivec3(glm::floor(p));
        const glm::vec3 f = p - glm::floor(p);
        const float c00 = glm::mix(at(i.x, i.y, i.z), at(i.x + 1, i.y, i.z), f.x);
        const float c10 = glm::mix(at(i.x, i.y + 1, i.z), at(i.x + 1, i.y + 1, i.z), f.x);
        const float c01 = glm::mix(at(i.x, i.y, i.z + 1), at(i.x + 1, i.y, i.z + 1), f.x);
        const float c11 = glm::mix(at(i.x, i.y + 1, i.z + 1), at(i.x + 1, i.y + 1, i.z + 1), f.x);
        r[v] = static_cast<std::uint8_t>(
          glm::mix(glm::mix(c00, c10, f.y), glm::mix(c01, c11, f.y), f.z) + 0.5f);
      }
  return r;
}
}

int main(int argc, char* argv[])
{
  if (argc < 5)
  {
    std::fprintf(stderr, "usage: cao-gpu-bench VOLUME.raw NX NY NZ [--rays 6,14,26,54] "
                         "[--poses N] [--upsample K] [--context auto|egl|osmesa] [--reach R]\n");
    return 2;
  }
  int dims[3] = { std::atoi(argv[2]), std::atoi(argv[3]), std::atoi(argv[4]) };
  std::vector<std::string> rays = { "6", "14", "26", "54" };
  int poses = 20, upsample = 1;
  double reach = 8.0;
  cao::gl::ContextKind kind = cao::gl::ContextKind::Auto;
  for (int i = 5; i < argc; ++i)
  {
    const std::string a = argv[i];
    const char* v = i + 1 < argc ? argv[i + 1] : "";
    if (a == "--rays")
    {
      rays.clear();
      std::stringstream ss(v);
      for (std::string r; std::getline(ss, r, ',');)
        rays.push_back(r);
      ++i;
    }
    else if (a == "--poses")
      poses = std::atoi(v), ++i;
    else if (a == "--upsample")
      upsample = std::atoi(v), ++i;
    else if (a == "--reach")
      reach = std::atof(v), ++i;
    else if (a == "--context")
    {
      const std::string k = v;
      kind = k == "egl" ? cao::gl::ContextKind::EGL
                        : (k == "osmesa" ? cao::gl::ContextKind::OSMesa : cao::gl::ContextKind::Auto);
      ++i;
    }
    else
      return Fail("unknown option " + a);
  }
  if (dims[0] < 1 || dims[1] < 1 || dims[2] < 1 || poses < 1 || upsample < 1 || !(reach > 0))
    return Fail("bad dimensions, pose count, upsampling or reach");
  std::ifstream file(argv[1], std::ios::binary);
  std::vector<std::uint8_t> scalars(static_cast<std::size_t>(dims[0]) * dims[1] * dims[2]);
  if (!file.read(reinterpret_cast<char*>(scalars.data()), static_cast<std::streamsize>(scalars.size())))
    return Fail(std::string("cannot read ") + std::to_string(scalars.size()) + " bytes from " + argv[1]);
  if (upsample > 1)
  {
    int up[3];
    scalars = Upsample(scalars, dims, upsample, up);
    std::copy(up, up + 3, dims);
  }
  std::string error;
  auto context = cao::gl::Context::CreateHeadless(kind, error);
  if (!context)
    return Fail(error);
  const std::int64_t voxels = std::int64_t(dims[0]) * dims[1] * dims[2];
  std::printf("cao-gpu-bench: %d x %d x %d (%lld voxels), reach %g voxels, %d poses\n"
              "context: %s (%s)\n",
    dims[0], dims[1], dims[2], (long long)voxels, reach, poses, context->Description().c_str(),
    cao::gl::ContextKindName(context->Kind()));

  // The CLI's default transfer function: 0 up to a quarter of the range,
  // then a ramp to 0.8; corrected for a step of one voxel.
  const auto range = std::minmax_element(scalars.begin(), scalars.end());
  const double lo = *range.first, hi = std::max<double>(*range.second, lo + 1.0);
  std::vector<float> table(256);
  for (int s = 0; s < 256; ++s)
  {
    const double q = lo + 0.25 * (hi - lo);
    const double a = s <= q ? 0.0 : std::min(0.8, 0.8 * (s - q) / (hi - q));
    table[s] = cao::CorrectOpacity(a, 1.0);
  }
  cao::gl::AOEngine engine(*context);
  cao::gl::VolumeUpload upload;
  std::copy(dims, dims + 3, upload.dims);
  upload.source = cao::gl::OpacitySource::Scalars8;
  upload.data = scalars.data();
  upload.opacityTable = table;
  if (!engine.SetVolume(upload, error))
    return Fail(error);

  const double radius = 0.25 * std::min({ dims[0], dims[1], dims[2] });
  cao::ClipScene scene;
  if (!scene.BuildSphere(radius, 0.5, 2, reach, error))
    return Fail(error);
  if (!engine.SetMaps(scene.camera.width, scene.camera.height, 2, scene.maps.front.data(),
        scene.maps.back.data(), scene.dilated.front.data(), scene.dilated.back.data(), error))
    return Fail(error);

  std::printf("\n| rays | full LAO ms | CAO update ms | speed-up | classify ms | copy ms | "
              "recompute ms | %% voxels in b | GPU bytes/voxel |\n"
              "|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const std::string& r : rays)
  {
    cao::VolumeGeometry g;
    std::copy(dims, dims + 3, g.dims);
    cao::LAOSettings settings; // the pattern given, one sample per voxel, no variation
    settings.quality = cao::Quality::Custom;
    settings.sampleDensity = 1.0;
    settings.variation = cao::RayVariation::None;
    int k = 64;
    if (!cao::ParseRayPattern(r, settings.pattern, k))
      return Fail("bad ray pattern " + r);
    settings.fibonacciRays = k;
    settings.reach = reach;
    cao::LAOPlan plan;
    if (!cao::BuildLAOPlan(g, settings, plan, error) || !engine.SetPlan(plan, error) ||
      !engine.Precompute(error))
      return Fail(error);
    const double full = engine.Times().precompute;
    if (!engine.SetMaps(scene.camera.width, scene.camera.height, 2, scene.maps.front.data(),
          scene.maps.back.data(), scene.dilated.front.data(), scene.dilated.back.data(), error))
      return Fail(error);
    double classify = 0, copy = 0, recompute = 0, affected = 0;
    for (int i = 0; i < poses; ++i)
    {
      // Along the diagonal, from outside one corner to outside the other.
      const float t = poses > 1 ? float(i) / float(poses - 1) : 0.5f;
      const glm::dvec3 a(-0.25 * dims[0], -0.25 * dims[1], -0.25 * dims[2]);
      const glm::dvec3 b(1.25 * dims[0], 1.25 * dims[1], 1.25 * dims[2]);
      const glm::dvec3 c = glm::mix(a, b, double(t));
      const double centre[3] = { c.x, c.y, c.z };
      cao::gl::UpdateStats stats;
      if (!engine.Update(scene.Pose(centre, 0.3 * i, dims, cao::layout::CAO_MODE_SUBTRACT, 16), stats, error))
        return Fail(error);
      const cao::gl::StageTimes& st = engine.Times();
      classify += st.classify;
      copy += st.copy;
      recompute += st.recompute;
      affected += double(stats.affected);
    }
    const double update = (classify + copy + recompute) / poses;
    std::printf("| %d | %.2f | %.3f | %.1fx | %.3f | %.3f | %.3f | %.2f | %.2f |\n", plan.rays, full,
      update, full / std::max(update, 1e-9), classify / poses, copy / poses, recompute / poses,
      100.0 * affected / (double(poses) * voxels), double(engine.ResidentBytes()) / voxels);
    std::fflush(stdout);
  }
  return 0;
}
