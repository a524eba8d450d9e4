#include "caoClipScene.h"

#include "caoClassify.h"

#include <algorithm>
#include <cmath>

namespace cao
{
bool ClipScene::BuildSphere(
  double radius, double pixel, int layers, double reach, std::string& error)
{
  const int rings = 24, segments = 48;
  const double pi = 3.14159265358979323846;
  points.clear();
  triangles.clear();
  points.insert(points.end(), { 0.0, 0.0, radius });
  for (int r = 1; r < rings; ++r)
  {
    const double t = pi * r / rings;
    for (int s = 0; s < segments; ++s)
    {
      const double p = 2.0 * pi * s / segments;
      points.insert(points.end(),
        { radius * std::sin(t) * std::cos(p), radius * std::sin(t) * std::sin(p),
          radius * std::cos(t) });
    }
  }
  points.insert(points.end(), { 0.0, 0.0, -radius });
  const std::int64_t south = static_cast<std::int64_t>(points.size() / 3) - 1;
  auto ring = [&](int r, int s) { return 1 + (r - 1) * segments + (s % segments); };
  for (int s = 0; s < segments; ++s)
  {
    triangles.insert(triangles.end(), { 0, ring(1, s), ring(1, s + 1) });
    for (int r = 1; r + 1 < rings; ++r)
    {
      triangles.insert(triangles.end(), { ring(r, s), ring(r + 1, s), ring(r + 1, s + 1) });
      triangles.insert(triangles.end(), { ring(r, s), ring(r + 1, s + 1), ring(r, s + 1) });
    }
    triangles.insert(triangles.end(), { ring(rings - 1, s), south, ring(rings - 1, s + 1) });
  }
  dilation = reach + 1.5 * std::sqrt(3.0);
  const double half = radius + dilation + 2.0 * pixel;
  camera = ClipCamera();
  camera.origin[0] = camera.origin[1] = -half;
  camera.origin[2] = 0.0;
  camera.pixelSize[0] = camera.pixelSize[1] = pixel;
  camera.width = camera.height = static_cast<int>(std::ceil(2.0 * half / pixel));
  camera.layers = layers;
  const TriangleMesh mesh = ViewMesh(points, triangles);
  if (!RasterizeDepthLayers(camera, mesh, maps, error))
    return false;
  dilated.Allocate(camera.width, camera.height, layers);
  eroded.Allocate(camera.width, camera.height, layers);
  DilateErodeRows(maps, camera, dilation, dilated, eroded, 0, camera.height);
  region[0] = 0.0;
  region[1] = camera.width;
  region[2] = 0.0;
  region[3] = camera.height;
  region[4] = -radius - dilation - 1.0;
  region[5] = radius + dilation + 1.0;
  return true;
}

layout::ClipParams ClipScene::Pose(
  const double c[3], double angle, const int dims[3], int mode, int aaSamples, bool narrow) const
{
  // index x -> local q = R^T (x - c); camera u = (q - o).right / ps, etc.
  const double cs = std::cos(angle), sn = std::sin(angle);
  const double Rt[3][3] = { { cs, sn, 0 }, { -sn, cs, 0 }, { 0, 0, 1 } };
  double affine[12];
  const double* axes[3] = { camera.right, camera.up, camera.direction };
  const double scale[3] = { camera.pixelSize[0], camera.pixelSize[1], 1.0 };
  for (int r = 0; r < 3; ++r)
  {
    double row[3] = { 0, 0, 0 };
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        row[j] += axes[r][k] * Rt[k][j];
    const double o = axes[r][0] * camera.origin[0] + axes[r][1] * camera.origin[1] +
      axes[r][2] * camera.origin[2];
    for (int j = 0; j < 3; ++j)
      affine[4 * r + j] = row[j] / scale[r];
    affine[4 * r + 3] = (-(row[0] * c[0] + row[1] * c[1] + row[2] * c[2]) - o) / scale[r];
  }
  layout::ClipParams clip{};
  for (int r = 0; r < 3; ++r)
    clip.toCamera[r] = { static_cast<float>(affine[4 * r]), static_cast<float>(affine[4 * r + 1]),
      static_cast<float>(affine[4 * r + 2]), static_cast<float>(affine[4 * r + 3]) };
  clip.map = { camera.width, camera.height, camera.layers, mode };
  SetAntiAliasingSamples(clip, aaSamples);
  int lo[3], hi[3];
  const ClipDepthMaps& cand = mode == layout::CAO_MODE_SUBTRACT ? dilated : eroded;
  const ClipMapsView view{ maps.front.data(), maps.back.data(), cand.front.data(),
    cand.back.data() };
  if (CandidateBox(affine, region, dims, lo, hi) &&
    (!narrow ||
      NarrowCandidateBox(affine, view, camera.width, camera.height, camera.layers, lo, hi)))
  {
    clip.boxMin = { lo[0], lo[1], lo[2], 0 };
    clip.boxMax = { hi[0], hi[1], hi[2], 0 };
  }
  else
  {
    clip.boxMin = { 1, 1, 1, 0 };
    clip.boxMax = { 0, 0, 0, 0 };
  }
  return clip;
}
}
