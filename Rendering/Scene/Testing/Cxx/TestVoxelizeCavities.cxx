// Seed 000's voxelizer on a real closed mesh with small cavities (the
// design notes' test for "cavities against depth slices"):
// Vented_Rear_Case_With_Pi_Supports.vtp (15 446 triangles, closed; vents
// and slots narrower than a voxel at 128 slices).
// - the parity fill against an independent point-in-mesh test (ray parity,
//   the majority of 3 directions, and the distance to the surface, through
//   cao::ClipShape::FromMesh) at 200 000 random voxel centres farther than
//   a voxel's half-diagonal from the surface: no voxel wrong, at 128, 256
//   and 512 slices;
// - what the grid fills near the surface, against the slices: the share of
//   the grid's volume that is air (in the vents and slots, and along every
//   face) but set by the default fill (parity plus surface voxels) falls as
//   the slices grow, and the parity alone never sets an outside centre
//   farther than a half-diagonal (its cavities are exact beyond the voxel
//   scale);
// - negative control: the same test against the mesh turned 90 degrees
//   (a wrong reference) finds thousands of wrong voxels.
#include "caoClipDepthMaps.h"
#include "caoClipGeometry.h"
#include "caoSceneGrid.h"
#include "vtkCAOInput.h"

#include "vtkPolyData.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

int TestVoxelizeCavities(int, char*[])
{
  const char* dir = std::getenv("CAO_DATA_DIR");
  const std::string path = std::string(dir ? dir : "Data") + "/Vented_Rear_Case_With_Pi_Supports.vtp";
  std::string error;
  vtkSmartPointer<vtkPolyData> mesh = vtkCAO::ReadMesh(path, error);
  if (!mesh)
  {
    std::printf("FAIL: %s\n", error.c_str());
    return 1;
  }
  std::vector<double> points;
  std::vector<std::int64_t> triangles;
  vtkCAO::TrianglesOf(mesh, points, triangles);
  const cao::MeshView view{ &points, &triangles };
  const std::int64_t open = cao::OpenEdges(view);
  std::printf("%s: %zu triangles, %lld open edges\n", path.c_str(), triangles.size() / 3,
    static_cast<long long>(open));
  int failures = open != 0;
  cao::TriangleMesh tm;
  tm.points = points.data();
  tm.numberOfPoints = static_cast<std::int64_t>(points.size() / 3);
  tm.triangles = triangles.data();
  tm.numberOfTriangles = static_cast<std::int64_t>(triangles.size() / 3);
  cao::ClipShape exact;
  if (!cao::ClipShape::FromMesh(tm, exact, error))
  {
    std::printf("FAIL: %s\n", error.c_str());
    return 1;
  }
  double b[6];
  exact.Bounds(b);
  const std::array<double, 6> bounds{ { b[0], b[1], b[2], b[3], b[4], b[5] } };
  double lastFilled = 1.0;
  std::uint64_t state = 0x2545F4914F6CDD1DULL;
  auto uniform = [&state]() {
    state ^= state << 13, state ^= state >> 7, state ^= state << 17;
    return static_cast<double>(state >> 11) * (1.0 / 9007199254740992.0);
  };
  for (int slices : { 128, 256, 512 })
  {
    cao::BitGrid parity, filled;
    if (!cao::VoxelizeWorld({ view }, bounds, 0.0, slices, parity, error, false) ||
      !cao::VoxelizeWorld({ view }, bounds, 0.0, slices, filled, error, true))
    {
      std::printf("FAIL: %s\n", error.c_str());
      return 1;
    }
    const double h = parity.voxel, halfDiagonal = 0.5 * std::sqrt(3.0) * h;
    std::int64_t far = 0, wrong = 0, turnedWrong = 0, near = 0, nearAir = 0, airFilled = 0, parityAirFar = 0;
    for (int s = 0; s < 200000; ++s)
    {
      const int i = std::min(parity.nx - 1, static_cast<int>(uniform() * parity.nx));
      const int j = std::min(parity.ny - 1, static_cast<int>(uniform() * parity.ny));
      const int k = std::min(parity.slices - 1, static_cast<int>(uniform() * parity.slices));
      const double p[3] = { parity.origin[0] + (i + 0.5) * h, parity.origin[1] + (j + 0.5) * h,
        parity.origin[2] + (k + 0.5) * h };
      const double d = exact.SignedDistance(p);
      const bool inside = d < 0.0;
      if (std::fabs(d) > halfDiagonal)
      {
        ++far;
        wrong += parity.Bit(i, j, k) != inside;
        parityAirFar += parity.Bit(i, j, k) && !inside;
        // The negative control: the reference asked at the point turned 90
        // degrees about z around the box's centre.
        const double cx = 0.5 * (b[0] + b[1]), cy = 0.5 * (b[2] + b[3]);
        const double q[3] = { cx - (p[1] - cy), cy + (p[0] - cx), p[2] };
        turnedWrong += parity.Bit(i, j, k) != (exact.SignedDistance(q) < 0.0);
      }
      else
      {
        ++near;
        if (!inside)
        {
          ++nearAir;
          airFilled += filled.Bit(i, j, k);
        }
      }
    }
    // The share of the grid's volume that is air but set: it shrinks with the voxels.
    const double fraction = static_cast<double>(airFilled) / 200000.0;
    std::printf("%4d slices (voxel %.3f): %lld of %lld centres beyond a half-diagonal wrong (turned "
                "reference: %lld); near the surface %lld, of them air %lld; air set by the default fill: %.2f%% of the grid\n",
      slices, h, static_cast<long long>(wrong), static_cast<long long>(far), static_cast<long long>(turnedWrong),
      static_cast<long long>(near), static_cast<long long>(nearAir), 100.0 * fraction);
    if (wrong != 0 || parityAirFar != 0 || far < 100000 || turnedWrong < 1000)
    {
      std::printf("FAIL: the parity fill at %d slices\n", slices);
      ++failures;
    }
    if (!(fraction < lastFilled) || nearAir < 500) // 500: enough samples to see the fall
    {
      std::printf("FAIL: the air the default fill sets near the surface does not fall with the slices\n");
      ++failures;
    }
    lastFilled = fraction;
  }
  std::printf("%d failure(s)\n", failures);
  return failures ? 1 : 0;
}
