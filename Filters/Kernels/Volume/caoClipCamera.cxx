#include "caoClipCamera.h"

#include "caoVectorMath.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>
#include <vector>

namespace cao
{
namespace
{
bool Finite(const double* v, int n)
{
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(v[i]))
      return false;
  return true;
}

template <typename T>
std::string Text(const T& streamed)
{
  std::ostringstream s;
  s << streamed;
  return s.str();
}
}

std::int64_t FirstNonFinitePoint(const double* points, std::int64_t n)
{
  for (std::int64_t i = 0; i < n; ++i)
    if (!Finite(points + 3 * i, 3))
      return i;
  return -1;
}

bool CheckClosedMesh(const TriangleMesh& mesh, ClosedMeshCheck& check, std::string& error)
{
  check = ClosedMeshCheck();
  const std::int64_t bad = FirstNonFinitePoint(mesh.points, mesh.numberOfPoints);
  if (bad >= 0)
  {
    error = "the clip mesh has a NaN or infinite coordinate (point " + std::to_string(bad) + ")";
    return false;
  }
  if (mesh.numberOfTriangles < 4)
  {
    error = "the clip mesh is degenerate: fewer than 4 non-degenerate triangles";
    return false;
  }
  std::vector<std::pair<std::int64_t, std::int64_t>> edges;
  edges.reserve(static_cast<std::size_t>(3 * mesh.numberOfTriangles));
  double volume = 0.0;
  for (std::int64_t t = 0; t < mesh.numberOfTriangles; ++t)
  {
    const std::int64_t* ids = mesh.triangles + 3 * t;
    for (int e = 0; e < 3; ++e)
    {
      if (ids[e] < 0 || ids[e] >= mesh.numberOfPoints)
      {
        error = "the clip mesh references a point id out of range";
        return false;
      }
      std::int64_t a = ids[e], b = ids[(e + 1) % 3];
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
    const double* a = mesh.points + 3 * ids[0];
    const double* b = mesh.points + 3 * ids[1];
    const double* c = mesh.points + 3 * ids[2];
    volume += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                a[2] * (b[0] * c[1] - b[1] * c[0])) /
      6.0;
  }
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i < edges.size();)
  {
    std::size_t j = i;
    while (j < edges.size() && edges[j] == edges[i])
      ++j;
    check.boundaryEdges += (j - i) == 1;
    check.nonManifoldEdges += (j - i) > 2;
    i = j;
  }
  double* bounds = check.bounds;
  bounds[0] = bounds[2] = bounds[4] = std::numeric_limits<double>::max();
  bounds[1] = bounds[3] = bounds[5] = -std::numeric_limits<double>::max();
  for (std::int64_t i = 0; i < mesh.numberOfPoints; ++i)
    for (int d = 0; d < 3; ++d)
    {
      bounds[2 * d] = std::min(bounds[2 * d], mesh.points[3 * i + d]);
      bounds[2 * d + 1] = std::max(bounds[2 * d + 1], mesh.points[3 * i + d]);
    }
  check.signedVolume = volume;
  if (check.boundaryEdges > 0)
  {
    error = "the clip mesh is open: " + std::to_string(check.boundaryEdges) +
      " edge(s) belong to a single triangle; clipping needs a closed surface";
    return false;
  }
  const double dx = bounds[1] - bounds[0], dy = bounds[3] - bounds[2], dz = bounds[5] - bounds[4];
  const double diag = std::sqrt(dx * dx + dy * dy + dz * dz);
  if (!(diag > 0.0) || !std::isfinite(diag))
  {
    error = "the clip mesh is degenerate: its bounds are empty or not finite";
    return false;
  }
  if (!(std::fabs(volume) > 1e-12 * diag * diag * diag))
  {
    error = "the clip mesh is degenerate: it encloses no volume";
    return false;
  }
  return true;
}

bool PlanClipCamera(
  const ClipCameraRequest& r, const TriangleMesh& mesh, ClipCameraPlan& plan, std::string& error)
{
  plan = ClipCameraPlan();
  // The settings, each against its stated range.
  const double* h = r.voxelSpacing;
  if (r.layers < 1 || r.layers > ClipMapLimits::MaxLayers)
    error = "NumberOfLayers must be 1 to " + std::to_string(ClipMapLimits::MaxLayers) +
      "; got " + std::to_string(r.layers);
  else if (!(h[0] > 0.0 && h[1] > 0.0 && h[2] > 0.0) || !Finite(h, 3))
    error = "VoxelSpacing must be positive and finite";
  else if (!(r.reach > 0.0) || !std::isfinite(r.reach))
    error = "the reach must be positive and finite (0 selects 8 voxel spacings); got " + Text(r.reach);
  else if (!(r.minimumPoseScale > 0.0) || !std::isfinite(r.minimumPoseScale))
    error = "MinimumPoseScale must be positive and finite; got " + Text(r.minimumPoseScale);
  else if (!(r.maximumPoseScale >= r.minimumPoseScale) || !std::isfinite(r.maximumPoseScale))
    error = "MaximumPoseScale must be finite and at least MinimumPoseScale (" +
      Text(r.minimumPoseScale) + "); got " + Text(r.maximumPoseScale);
  else if (!(r.dilationScale >= 0.0) || !std::isfinite(r.dilationScale))
    error = "DilationScale must be non-negative and finite";
  else if (!(r.pixelSize >= 0.0) || !std::isfinite(r.pixelSize))
    error = r.pixelSizeName + " must be 0 (derived) or a positive, finite length; got " + Text(r.pixelSize);
  else if (!std::isfinite(r.margin))
    error = "Margin must be finite (negative: derived)";
  else if (!Finite(r.cameraExtent, 4) || !Finite(r.direction, 3) || !Finite(r.viewUp, 3))
    error = "CameraExtent, Direction and ViewUp must be finite";
  else if (r.resolution[0] < 0 || r.resolution[1] < 0 ||
    (r.resolution[0] > 0) != (r.resolution[1] > 0))
    error = "the clipping camera has zero area: Resolution (" + std::to_string(r.resolution[0]) +
      ", " + std::to_string(r.resolution[1]) + ") must be both positive or both 0";
  if (!error.empty())
    return false;
  if (mesh.numberOfPoints < 3 || FirstNonFinitePoint(mesh.points, mesh.numberOfPoints) >= 0)
  {
    error = "the clip mesh has no finite points";
    return false;
  }

  // Camera frame: right x up = direction.
  ClipCamera& cam = plan.camera;
  Vec3 dir = LoadVec3(r.direction);
  if (DivideByLength(dir) == 0.0)
  {
    error = "the clipping camera's Direction is zero";
    return false;
  }
  Vec3 right = glm::cross(LoadVec3(r.viewUp), dir);
  if (DivideByLength(right) < 1e-12)
  {
    error = "the clipping camera's ViewUp is parallel to its Direction";
    return false;
  }
  Vec3 up = glm::cross(dir, right);
  DivideByLength(up);
  StoreVec3(dir, cam.direction);
  StoreVec3(right, cam.right);
  StoreVec3(up, cam.up);
  cam.layers = r.layers;

  // Projected bounds of the mesh.
  const double big = std::numeric_limits<double>::max();
  double umin = big, umax = -big, vmin = big, vmax = -big, zmin = big, zmax = -big;
  for (std::int64_t i = 0; i < mesh.numberOfPoints; ++i)
  {
    const Vec3 p = LoadVec3(mesh.points + 3 * i);
    const double u = glm::dot(p, right), v = glm::dot(p, up), z = glm::dot(p, dir);
    umin = std::min(umin, u);
    umax = std::max(umax, u);
    vmin = std::min(vmin, v);
    vmax = std::max(vmax, v);
    zmin = std::min(zmin, z);
    zmax = std::max(zmax, z);
  }
  if (!(umax > umin) || !(vmax > vmin))
  {
    error = "the clip mesh projects to zero area along the camera direction";
    return false;
  }

  // Dilation radius: reach + trilinear footprint (one cell diagonal) +
  // anti-aliasing footprint (half a diagonal), over the smallest pose scale,
  // plus slack for float rounding of the camera coordinates (~100 ulps of
  // the camera's coordinate range).
  const double voxelDiagonal = glm::length(LoadVec3(h));
  const double nominal =
    r.dilationScale * (r.reach + 1.5 * voxelDiagonal) / r.minimumPoseScale;
  const double range = std::max({ umax - umin, vmax - vmin, zmax - zmin }) + 2.0 * nominal +
    std::max({ std::fabs(umin), std::fabs(umax), std::fabs(vmin), std::fabs(vmax),
      std::fabs(zmin), std::fabs(zmax) });
  const double radius = nominal + 1e-5 * range;
  plan.radius = radius;
  plan.voxelDiagonal = voxelDiagonal;
  if (!std::isfinite(radius))
  {
    error = "the dilation radius overflows (reach " + Text(r.reach) + ", MinimumPoseScale " +
      Text(r.minimumPoseScale) + ")";
    return false;
  }

  // The part of the image plane the maps must cover: the mesh, or only
  // where it can meet the volume.
  double tu0 = umin, tu1 = umax, tv0 = vmin, tv1 = vmax;
  const double inf = std::numeric_limits<double>::infinity();
  double valid[4] = { -inf, inf, -inf, inf };
  const double* roi = r.regionOfInterest;
  const bool customExtent = r.cameraExtent[0] != 0.0 || r.cameraExtent[1] != 0.0 ||
    r.cameraExtent[2] != 0.0 || r.cameraExtent[3] != 0.0;
  if (roi[0] <= roi[1] && roi[2] <= roi[3] && roi[4] <= roi[5] && !customExtent)
  {
    if (!Finite(roi, 6))
    {
      error = "the region of interest must be finite";
      return false;
    }
    double ru0 = big, ru1 = -big, rv0 = big, rv1 = -big;
    for (int c = 0; c < 8; ++c)
    {
      const Vec3 q = { roi[(c & 1)], roi[2 + ((c >> 1) & 1)], roi[4 + ((c >> 2) & 1)] };
      ru0 = std::min(ru0, glm::dot(q, right));
      ru1 = std::max(ru1, glm::dot(q, right));
      rv0 = std::min(rv0, glm::dot(q, up));
      rv1 = std::max(rv1, glm::dot(q, up));
    }
    if (ru0 > umin || ru1 < umax || rv0 > vmin || rv1 < vmax)
    {
      // The mesh reaches beyond the region: cover the region only (where
      // it meets the mesh, or the region itself when they do not meet).
      tu0 = std::max(umin, ru0);
      tu1 = std::min(umax, ru1);
      tv0 = std::max(vmin, rv0);
      tv1 = std::min(vmax, rv1);
      if (!(tu1 > tu0) || !(tv1 > tv0))
      {
        tu0 = ru0;
        tu1 = ru1;
        tv0 = rv0;
        tv1 = rv1;
      }
      valid[0] = ru0;
      valid[1] = ru1;
      valid[2] = rv0;
      valid[3] = rv1;
    }
  }
  std::copy(valid, valid + 4, plan.validRegion);

  // Extent and resolution.
  double pw = 0.0, ph = 0.0;
  int width = 0, height = 0;
  double eu0, eu1, ev0, ev1;
  const double nominalPixel = 0.5 * std::min({ h[0], h[1], h[2] }) / r.maximumPoseScale;
  plan.derivedPixel = r.pixelSize <= 0.0 && r.resolution[0] == 0;
  if (customExtent)
  {
    eu0 = r.cameraExtent[0];
    eu1 = r.cameraExtent[1];
    ev0 = r.cameraExtent[2];
    ev1 = r.cameraExtent[3];
    if (!(eu1 > eu0) || !(ev1 > ev0))
    {
      error = "the clipping camera has zero area: CameraExtent (" + Text(eu0) + ", " + Text(eu1) +
        ", " + Text(ev0) + ", " + Text(ev1) + ")";
      return false;
    }
    if (r.resolution[0] > 0)
    {
      width = r.resolution[0];
      height = r.resolution[1];
      pw = (eu1 - eu0) / width;
      ph = (ev1 - ev0) / height;
    }
    else
    {
      pw = ph = r.pixelSize > 0.0 ? r.pixelSize : nominalPixel;
      const double w = std::ceil((eu1 - eu0) / pw), hh = std::ceil((ev1 - ev0) / ph);
      if (!(w * hh * r.layers <= static_cast<double>(ClipMapLimits::MaxPixelLayers)))
      {
        error = "too many pixels: the camera extent at pixel size " + Text(pw) + " needs " + Text(w) + " x " + Text(hh) +
          " pixels x " + std::to_string(r.layers) + " layers, above the limit of " +
          std::to_string(ClipMapLimits::MaxPixelLayers) + "; set a larger " + r.pixelSizeName;
        return false;
      }
      width = static_cast<int>(w);
      height = static_cast<int>(hh);
    }
    if (umin - radius - pw < eu0 || umax + radius + pw > eu1 || vmin - radius - ph < ev0 ||
      vmax + radius + ph > ev1)
    {
      error = "CameraExtent does not contain the clip mesh dilated by " + Text(radius) +
        " plus one pixel; enlarge it or leave it at 0 to derive it";
      return false;
    }
  }
  else
  {
    if (r.resolution[0] > 0)
    {
      width = r.resolution[0];
      height = r.resolution[1];
      if (width < 5 || height < 5)
      {
        error = "the clipping camera has (nearly) zero area: Resolution must be at least 5x5";
        return false;
      }
      if (r.margin >= 0.0)
      {
        pw = (tu1 - tu0 + 2.0 * r.margin) / width;
        ph = (tv1 - tv0 + 2.0 * r.margin) / height;
      }
      else
      {
        pw = (tu1 - tu0 + 2.0 * radius) / (width - 4);
        ph = (tv1 - tv0 + 2.0 * radius) / (height - 4);
      }
    }
    else if (r.pixelSize > 0.0)
    {
      pw = ph = r.pixelSize;
    }
    else
    {
      // Derived: half a voxel in the world at the largest pose scale, but no
      // finer than radius / 32 (the dilation window stays ~65 x 65 pixels)
      // unless the mesh is smaller than 8 such pixels; and within the limits.
      const double meshSpan = std::min(tu1 - tu0, tv1 - tv0);
      pw = ph = std::max(nominalPixel, std::min(radius / 32.0, meshSpan / 8.0));
      const double margin = r.margin >= 0.0 ? r.margin : radius + 2.0 * pw;
      const double span = std::max(tu1 - tu0, tv1 - tv0) + 2.0 * margin;
      if (span / pw > ClipMapLimits::MaxDerivedPixelsPerAxis)
        pw = ph = span / ClipMapLimits::MaxDerivedPixelsPerAxis;
    }
    // A derived pixel grows (by 1.25x steps) until the maps fit the limits;
    // a given one makes it an error below.
    for (int attempt = 0; attempt < 200; ++attempt)
    {
      const double marginU = r.margin >= 0.0 ? r.margin : radius + 2.0 * pw;
      const double marginV = r.margin >= 0.0 ? r.margin : radius + 2.0 * ph;
      if (marginU < radius + pw || marginV < radius + ph)
      {
        error = "Margin " + Text(r.margin) + " leaves no room for the dilation radius " +
          Text(radius) + " plus one pixel";
        return false;
      }
      eu0 = tu0 - marginU;
      ev0 = tv0 - marginV;
      if (r.resolution[0] > 0)
      {
        eu1 = eu0 + width * pw;
        ev1 = ev0 + height * ph;
        break;
      }
      const double w = std::ceil((tu1 + marginU - eu0) / pw);
      const double hh = std::ceil((tv1 + marginV - ev0) / ph);
      const double window =
        (2.0 * std::ceil(radius / pw) + 3.0) * (2.0 * std::ceil(radius / ph) + 3.0);
      const bool fits = w * hh * r.layers <= static_cast<double>(ClipMapLimits::MaxPixelLayers) &&
        w * hh * r.layers * window <= ClipMapLimits::MaxDilationWork;
      if (fits || !plan.derivedPixel)
      {
        width = static_cast<int>(std::min(w, 1e9));
        height = static_cast<int>(std::min(hh, 1e9));
        eu1 = eu0 + width * pw;
        ev1 = ev0 + height * ph;
        break;
      }
      pw = ph = pw * 1.25;
    }
    if (plan.derivedPixel && pw > nominalPixel * (1.0 + 1e-12) &&
      pw > std::min(radius / 32.0, std::min(tu1 - tu0, tv1 - tv0) / 8.0) * (1.0 + 1e-12))
    {
      plan.note = "the derived depth-map pixel (half a voxel at the largest pose scale, " +
        Text(nominalPixel) + " local units) was coarsened to " + Text(pw) +
        " so that the maps of a clip mesh this large (" + Text(tu1 - tu0) + " x " +
        Text(tv1 - tv0) + " local units) fit the limits; the clip is exact to that pixel. "
        "Give a region of interest (the part the volume can reach) to keep half-voxel pixels";
    }
  }
  if (!(pw > 0.0) || !(ph > 0.0) || width < 1 || height < 1 || !std::isfinite(pw * ph))
  {
    error = "the clipping camera has zero area";
    return false;
  }
  const double pixelLayers = static_cast<double>(width) * height * r.layers;
  if (pixelLayers > static_cast<double>(ClipMapLimits::MaxPixelLayers))
  {
    error = "too many pixels: the clipping camera would need " + std::to_string(width) + " x " +
      std::to_string(height) + " pixels x " + std::to_string(r.layers) +
      " layers, above the limit of " + std::to_string(ClipMapLimits::MaxPixelLayers) +
      " (1.5 GiB of maps); set a larger " + r.pixelSizeName + " (it is " + Text(pw) + ")";
    return false;
  }
  // The dilation visits (2 r + 3)^2 window pixels per pixel, r = radius / pixel.
  const double window = (2.0 * std::ceil(radius / pw) + 3.0) * (2.0 * std::ceil(radius / ph) + 3.0);
  if (pixelLayers * window > ClipMapLimits::MaxDilationWork)
  {
    error = "too many pixels to dilate: the dilation radius " + Text(radius) + " spans " + Text(std::ceil(radius / pw)) +
      " pixels of size " + Text(pw) + ": " + Text(pixelLayers) + " pixel-layers x a window of " +
      Text(window) + " is above the limit of " + Text(ClipMapLimits::MaxDilationWork) +
      "; set a larger " + r.pixelSizeName;
    return false;
  }
  cam.pixelSize[0] = pw;
  cam.pixelSize[1] = ph;
  cam.width = width;
  cam.height = height;
  for (int d = 0; d < 3; ++d)
    cam.origin[d] = eu0 * right[d] + ev0 * up[d];
  return true;
}
}
