// Seed 000's CPU twin (caoVoxelConeTracing):
// - the voxelizer: a cube whose vertices and edges lie exactly on column
//   centres fills exactly 15^3 voxels (the top-left rule counts each
//   shared edge once; negative control: the same cube shifted by half a
//   voxel fills 16^3 or 14^3 columns... its own exact count); a sphere's
//   parity equals the analytic interior at every voxel centre farther
//   than the tessellation's sagitta from the surface; two overlapping
//   closed spheres stay solid (OR of fills, not XOR); an open mesh is
//   reported (its boundary edges) and filled as a shell;
// - cone tracing against its own definition: a solid half-space x > a
//   voxelized finely, against the same cones, spheres and prisms with each
//   prism's chord counted exactly (occupancy "volume") or each ray's reach
//   beyond the plane ("rays");
//   negative control: a coarse grid misses it by more; an empty grid
//   gives AO 1 exactly; a point on a solid floor stays open;
// - a thin roof at 0.3 R over P: the rays within 0.1 of the reference's
//   (H/R)^2; negative control: the volume fraction, more than 0.3 lighter;
// - the eye grid: a scene turned by R^T in a grid of frame R gives the
//   world grid's AO (to rounding) at the turned points; negative control:
//   the wrong frame (R^T) does not;
// - InsideMask against the analytic interior of a sphere under an
//   anisotropic, shifted index map; an open mesh is refused;
// - the volume occluding surfaces: in a homogeneous medium of opacity a per
//   unit distance, and no voxel near, the AO is the transmittance
//   (1 - a)^(sum of the spheres' diameters / unit) exactly; the medium
//   carved away (opacity 0) gives 1; a trilinear field is sampled exactly;
// - bands: a wall on a floor; the 4 x 4 pattern and filter (the default)
//   keep the floor's ripple (RMS second difference of the AO) within 2 x
//   the reference's own; negative control: without it, more than 3 x the
//   pattern's;
// - bad input: slices, settings, ids, the filter's tolerance.
#include "caoVoxelConeTracing.h"
#include "caoSurfaceTestScenes.h"
#include "caoTestUtilities.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace
{
const double Pi = 3.14159265358979323846;

void Box(double lo, double hi, std::vector<double>& p, std::vector<std::int64_t>& t)
{
  p = { lo, lo, lo, hi, lo, lo, hi, hi, lo, lo, hi, lo, lo, lo, hi, hi, lo, hi, hi, hi, hi, lo, hi, hi };
  t = { 0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4, 2, 3, 7, 2, 7, 6, 1, 2, 6, 1, 6, 5, 3, 0, 4, 3, 4, 7 };
}

/// Fraction of a sphere (centre c, radius r) in the half-space x > a.
double CapFraction(double cx, double r, double a)
{
  const double d = a - cx; // signed distance of the plane from the centre
  if (d >= r)
    return 0.0;
  if (d <= -r)
    return 1.0;
  const double hcap = r - d; // height of the cap x > a
  return Pi * hcap * hcap * (3 * r - hcap) / 3.0 / (4.0 / 3.0 * Pi * r * r * r);
}
}

int TestVoxelConeTracing(int, char*[])
{
  std::string error;
  // OpenEdges: a box whose triangles each have their own three points (as
  // STL gives them) is closed; one triangle less opens 3 edges; a third
  // triangle on an edge makes it non-manifold (counted); with a NaN
  // coordinate no point is merged (negative control: all 36 edges open).
  {
    std::vector<double> p, q;
    std::vector<std::int64_t> t, s;
    Box(0.0, 1.0, p, t);
    for (std::int64_t id : t)
    {
      q.insert(q.end(), { p[3 * id], p[3 * id + 1], p[3 * id + 2] });
      s.push_back(static_cast<std::int64_t>(s.size()));
    }
    const std::int64_t closed = cao::OpenEdges({ &q, &s });
    std::vector<std::int64_t> cut(s.begin() + 3, s.end());
    const std::int64_t opened = cao::OpenEdges({ &q, &cut });
    std::vector<double> fin = q;
    std::vector<std::int64_t> three = s;
    fin.insert(fin.end(), { 0.5, 0.5, 2.0 });
    three.insert(three.end(), { 0, 1, static_cast<std::int64_t>(fin.size() / 3 - 1) });
    const std::int64_t nonManifold = cao::OpenEdges({ &fin, &three });
    std::vector<double> nan = q;
    nan[0] = std::nan("");
    const std::int64_t unmerged = cao::OpenEdges({ &nan, &s });
    std::printf("open edges: closed box (unshared points) %lld, one triangle less %lld, a third triangle on an "
                "edge %lld, a NaN (no merging) %lld\n",
      static_cast<long long>(closed), static_cast<long long>(opened), static_cast<long long>(nonManifold),
      static_cast<long long>(unmerged));
    CAO_CHECK(closed == 0 && opened == 3 && nonManifold == 3 && unmerged == 36, "open edges %lld %lld %lld %lld",
      static_cast<long long>(closed), static_cast<long long>(opened), static_cast<long long>(nonManifold),
      static_cast<long long>(unmerged));
    // Degenerate triangles by their ids (i, i, j and i, i, i) added to the
    // closed box leave it closed (they had made its edges non-manifold); a
    // third real triangle on an edge, the control above, still counts.
    std::vector<std::int64_t> degenerate = s;
    degenerate.insert(degenerate.end(), { s[0], s[0], s[1], s[2], s[2], s[2], s[3], s[4], s[3] });
    const std::int64_t withDegenerate = cao::OpenEdges({ &q, &degenerate });
    CAO_CHECK(withDegenerate == 0, "a closed box with 3 degenerate triangles: %lld open edges (0 expected)",
      static_cast<long long>(withDegenerate));
  }
  // The cube on column centres: h = 1/16, origin -1; vertices at
  // -1 + 8.5/16 and -1 + 23.5/16.
  {
    std::vector<double> p;
    std::vector<std::int64_t> t;
    Box(-1 + 8.5 / 16, -1 + 23.5 / 16, p, t);
    cao::BitGrid grid;
    CAO_CHECK(cao::VoxelizeWorld({ { &p, &t } }, { { -1, 1, -1, 1, -1, 1 } }, 0.0, 32, grid, error, false),
      "%s", error.c_str());
    CAO_CHECK(grid.voxel == 1.0 / 16 && grid.nx == 32 && grid.origin[0] == -1.0, "grid h %g nx %d origin %g",
      grid.voxel, grid.nx, grid.origin[0]);
    // A radius under the voxel cannot be resolved by the cones (they read
    // the surface they start from): said; at one voxel and above, not.
    CAO_CHECK(!cao::VCTUnresolvedRadius(0.99 / 16, grid).empty() &&
        cao::VCTUnresolvedRadius(1.0 / 16, grid).empty() && cao::VCTUnresolvedRadius(0.5, grid).empty(),
      "the unresolved radius is the one under a voxel");
    std::printf("cube with vertices on column centres: %lld voxels set (15^3 = 3375), open edges %lld\n",
      static_cast<long long>(grid.CountAll()), static_cast<long long>(grid.openEdges[0]));
    CAO_CHECK(grid.CountAll() == 3375 && grid.openEdges[0] == 0, "%lld", static_cast<long long>(grid.CountAll()));
    // Negative control: an inclusive rule (both triangles own a shared
    // edge) would cancel the parity on the face diagonals and double the
    // boundary columns; the count here would not be a cube.
    for (int j = 0; j < grid.ny; ++j)
      for (int i = 0; i < grid.nx; ++i)
      {
        const int n = grid.CountBits(i, j, 0, 31);
        const bool in = i >= 8 && i <= 22 && j >= 8 && j <= 22;
        CAO_CHECK(n == (in ? 15 : 0), "column %d %d: %d bits", i, j, n);
      }
    // With the surface voxels: the bottom face's crossing (slice
    // coordinate 8.5) adds slice 8 under each column; the top face's
    // (23.5) is slice 23, already inside: 15 x 15 x 16.
    cao::BitGrid withSurface;
    CAO_CHECK(cao::VoxelizeWorld({ { &p, &t } }, { { -1, 1, -1, 1, -1, 1 } }, 0.0, 32, withSurface, error),
      "%s", error.c_str());
    std::printf("the same cube with its surface voxels: %lld (15 x 15 x 16 = 3600)\n",
      static_cast<long long>(withSurface.CountAll()));
    CAO_CHECK(withSurface.CountAll() == 3600 && withSurface.CountBits(8, 8, 8, 8) == 1, "%lld",
      static_cast<long long>(withSurface.CountAll()));
  }
  // A sphere: parity = analytic interior away from the surface.
  std::vector<double> sp;
  std::vector<std::int64_t> st;
  caotest::UVSphere(0.6, 128, sp, st);
  {
    cao::BitGrid grid;
    CAO_CHECK(cao::VoxelizeWorld({ { &sp, &st } }, { { -0.6, 0.6, -0.6, 0.6, -0.6, 0.6 } }, 0.1, 128,
                grid, error, false), "%s", error.c_str());
    const double sagitta = 0.6 * (1 - std::cos(Pi / 128)) * 2; // rings and segments
    std::int64_t wrong = 0, checked = 0, inside = 0;
    for (int j = 0; j < grid.ny; ++j)
      for (int i = 0; i < grid.nx; ++i)
        for (int k = 0; k < grid.slices; ++k)
        {
          const double x = grid.origin[0] + (i + 0.5) * grid.voxel, y = grid.origin[1] + (j + 0.5) * grid.voxel,
                       z = grid.origin[2] + (k + 0.5) * grid.voxel;
          const double d = std::sqrt(x * x + y * y + z * z) - 0.6;
          if (std::fabs(d) <= sagitta + 1e-12)
            continue;
          ++checked;
          inside += d < 0;
          wrong += grid.Bit(i, j, k) != (d < 0);
        }
    std::printf("sphere r=0.6, 128 slices: %lld of %lld voxel centres checked wrong (%lld inside)\n",
      static_cast<long long>(wrong), static_cast<long long>(checked), static_cast<long long>(inside));
    CAO_CHECK(wrong == 0 && inside > 100000, "%lld wrong", static_cast<long long>(wrong));
    // With the surface voxels: a superset, every added voxel within a
    // voxel's half-diagonal (and the sagitta) of the sphere.
    cao::BitGrid filled;
    CAO_CHECK(cao::VoxelizeWorld({ { &sp, &st } }, { { -0.6, 0.6, -0.6, 0.6, -0.6, 0.6 } }, 0.1, 128,
                filled, error), "%s", error.c_str());
    std::int64_t added = 0, far = 0, lost = 0;
    for (int j = 0; j < grid.ny; ++j)
      for (int i = 0; i < grid.nx; ++i)
        for (int k = 0; k < grid.slices; ++k)
        {
          const bool a = grid.Bit(i, j, k), b = filled.Bit(i, j, k);
          lost += a && !b;
          if (b && !a)
          {
            ++added;
            const double x = grid.origin[0] + (i + 0.5) * grid.voxel, y = grid.origin[1] + (j + 0.5) * grid.voxel,
                         z = grid.origin[2] + (k + 0.5) * grid.voxel;
            far += std::fabs(std::sqrt(x * x + y * y + z * z) - 0.6) > 0.5 * std::sqrt(3.0) * grid.voxel + sagitta;
          }
        }
    std::printf("with surface voxels: %lld added (all within a half-diagonal of the sphere: %lld beyond), %lld lost\n",
      static_cast<long long>(added), static_cast<long long>(far), static_cast<long long>(lost));
    CAO_CHECK(added > 1000 && far == 0 && lost == 0, "surface voxels: %lld added, %lld far, %lld lost",
      static_cast<long long>(added), static_cast<long long>(far), static_cast<long long>(lost));
    // Two overlapping spheres: their union, solid (a shared XOR would hollow the overlap).
    std::vector<double> sp2 = sp;
    for (std::size_t c = 0; c < sp2.size(); c += 3)
      sp2[c] += 0.3;
    cao::BitGrid two;
    CAO_CHECK(cao::VoxelizeWorld({ { &sp, &st }, { &sp2, &st } }, { { -0.6, 0.9, -0.6, 0.6, -0.6, 0.6 } },
                0.1, 128, two, error), "%s", error.c_str());
    const int ci = static_cast<int>(std::floor((0.15 - two.origin[0]) / two.voxel));
    const int cj = static_cast<int>(std::floor((0.0 - two.origin[1]) / two.voxel));
    const int ck = static_cast<int>(std::floor((0.0 - two.origin[2]) / two.voxel));
    CAO_CHECK(two.Bit(ci, cj, ck), "the overlap of two closed spheres stays solid");
    // An open mesh: the sphere less one triangle.
    std::vector<std::int64_t> holed(st.begin() + 3, st.end());
    cao::BitGrid shell;
    CAO_CHECK(cao::VoxelizeWorld({ { &sp, &holed } }, { { -0.6, 0.6, -0.6, 0.6, -0.6, 0.6 } }, 0.1, 128,
                shell, error), "%s", error.c_str());
    std::printf("the sphere less one triangle: %lld open edges, filled as a shell: %lld voxels (solid: %lld)\n",
      static_cast<long long>(shell.openEdges[0]), static_cast<long long>(shell.CountAll()),
      static_cast<long long>(grid.CountAll()));
    CAO_CHECK(shell.openEdges[0] == 3 && shell.CountAll() < grid.CountAll() / 4 && shell.CountAll() > 1000,
      "open mesh: %lld edges, %lld voxels", static_cast<long long>(shell.openEdges[0]),
      static_cast<long long>(shell.CountAll()));
    // The sphere in two pieces (as on two processes): their PieceBits
    // parities XOR into the whole sphere's, closed; with the pieces'
    // surface voxels OR-ed, the grid FillGrid makes of the whole sphere,
    // bit for bit (`filled`, with its surface voxels). One piece alone is
    // not closed (the negative control).
    std::vector<std::int64_t> west, east;
    for (std::size_t f = 0; f + 2 < st.size(); f += 3)
    {
      const double x = sp[3 * st[f]] + sp[3 * st[f + 1]] + sp[3 * st[f + 2]];
      (x < 0.1 ? west : east).insert((x < 0.1 ? west : east).end(), { st[f], st[f + 1], st[f + 2] });
    }
    std::vector<std::uint32_t> parityWest, parityEast, surface, shellBits;
    const bool made = cao::PieceBits({ &sp, &west }, grid, &parityWest, &surface, &shellBits, error) &&
      cao::PieceBits({ &sp, &east }, grid, &parityEast, &surface, &shellBits, error);
    CAO_CHECK(made, "%s", error.c_str());
    const bool halfClosed = cao::ParityClosed(grid, parityWest);
    std::vector<std::uint32_t> joined(parityWest.size());
    long long apart = 0, shellOutside = 0;
    for (std::size_t w = 0; w < joined.size(); ++w)
    {
      joined[w] = (parityWest[w] ^ parityEast[w]) | surface[w];
      apart += joined[w] != filled.bits[w];
      shellOutside += __builtin_popcount(shellBits[w] & ~filled.bits[w]);
    }
    const bool closed = cao::ParityClosed(grid, [&] {
      std::vector<std::uint32_t> x(parityWest.size());
      for (std::size_t w = 0; w < x.size(); ++w)
        x[w] = parityWest[w] ^ parityEast[w];
      return x;
    }());
    // Their open edges matched up: none (each half alone has its cut).
    std::vector<double> edgesWest, edgesEast, edgesHoled;
    const std::int64_t cutWest = cao::OpenEdges({ &sp, &west }, edgesWest);
    cao::OpenEdges({ &sp, &east }, edgesEast);
    std::vector<double> both = edgesWest;
    both.insert(both.end(), edgesEast.begin(), edgesEast.end());
    std::vector<std::int64_t> eastHoled(east.begin() + 3, east.end());
    cao::OpenEdges({ &sp, &eastHoled }, edgesHoled);
    std::vector<double> holedBoth = edgesWest;
    holedBoth.insert(holedBoth.end(), edgesHoled.begin(), edgesHoled.end());
    // (One half's points moved by a rounding, as pieces made apart may place
    // a shared point: matched within the tolerance, not without.)
    std::vector<double> nudged = both;
    for (std::size_t i = 0; i < edgesWest.size(); i += 7)
      nudged[i] += 1e-15;
    const std::int64_t matched = cao::OpenEdgesOfPieces(both, 1e-9),
                       stillOpen = cao::OpenEdgesOfPieces(holedBoth, 1e-9),
                       nudgedMatched = cao::OpenEdgesOfPieces(nudged, 1e-9),
                       nudgedExact = cao::OpenEdgesOfPieces(nudged, 0.0);
    std::printf("the two halves' open edges: %lld on the west half alone, %lld matched up, %lld with a triangle "
                "less on the east half; one half moved by 1e-15: %lld within 1e-9, %lld compared exactly\n",
      static_cast<long long>(cutWest), static_cast<long long>(matched), static_cast<long long>(stillOpen),
      static_cast<long long>(nudgedMatched), static_cast<long long>(nudgedExact));
    CAO_CHECK(cutWest > 0 && matched == 0 && stillOpen == 3 && nudgedMatched == 0 && nudgedExact > 0,
      "pieces' open edges %lld %lld %lld %lld %lld", static_cast<long long>(cutWest),
      static_cast<long long>(matched), static_cast<long long>(stillOpen), static_cast<long long>(nudgedMatched),
      static_cast<long long>(nudgedExact));
    std::printf("the sphere in two pieces: parities XOR-ed %s closed, one piece %s closed, with the surface "
                "voxels %lld words apart from the whole sphere's grid; the pieces' shells: %lld voxels "
                "outside it\n",
      closed ? "are" : "are not", halfClosed ? "is" : "is not", apart, shellOutside);
    CAO_CHECK(closed && !halfClosed && apart == 0, "pieces: closed %d, half closed %d, %lld words apart",
      int(closed), int(halfClosed), apart);
  }
  // Cone tracing against its own definition: half-space x > a (a box
  // slab), P at the origin with n = +z: each sphere's occupied fraction is
  // the cap beyond x = a (occupancy "volume", the paper's), or the share of
  // its rays that reach beyond x = a ("rays").
  for (cao::VCTOccupancy occupancy : { cao::VCTOccupancy::Volume, cao::VCTOccupancy::Rays })
  {
    for (double a : { 0.1, 0.3 })
    {
      std::vector<double> p = { a, -3, -3, 3, -3, -3, 3, 3, -3, a, 3, -3, a, -3, 3, 3, -3, 3, 3, 3, 3, a, 3, 3 };
      std::vector<std::int64_t> t;
      std::vector<double> dummy;
      Box(0, 1, dummy, t); // the box's triangles, on these 8 points
      cao::VCTSettings s;
      s.quality = cao::Quality::Custom;
      s.spheres = 5;
      s.prisms = 32;
      s.radius = 1.0;
      s.apexOffset = 0.0;
      s.occupancy = occupancy;
      double error2[2] = { 0, 0 };
      double exactAO = 0;
      for (int fine = 1; fine >= 0; --fine)
      {
        s.slices = fine ? 1024 : 32;
        cao::BitGrid grid;
        // The parity alone: the exact value below is for the solid x > a.
        CAO_CHECK(cao::VoxelizeWorld({ { &p, &t } }, { { -1.1, 1.1, -1.1, 1.1, -1.1, 1.1 } }, 0.0, s.slices,
                    grid, error, false), "%s", error.c_str());
        cao::VCTPlan plan;
        s.surfaceVoxels = false;
        CAO_CHECK(cao::BuildVCTPlan(s, grid, plan, error), "%s", error.c_str());
        // The exact value of the same cones, spheres and prisms: a prism
        // (a chord along z) lies wholly in x > a or wholly out of it, so a
        // sphere's occupied fraction is the chord-weighted share of the
        // prisms beyond the plane (occupancy "volume"); a ray apex + tau r,
        // sampled at tau = t0 + (m + 1/2) step up to t1 - step / 2, meets
        // x > a if and only if (t1 - step / 2) r_x > a, so a cone's
        // occlusion is the cosine-weighted share of those rays ("rays"). (The spherical cap's volume fraction, the limit of many
        // prisms, is printed beside it.)
        const double n[3] = { 0, 0, 1 }, o[3] = { 0, 0, 0 };
        double occ = 0.0, capOcc = 0.0;
        for (std::size_t c = 0; c < plan.cones.size(); ++c)
        {
          // ConeTraceAO's frame for n = +z: tx = (1, 0, 0), ty = (0, 1, 0).
          const double dx = plan.cones[c][0];
          double open = 1.0, capOpen = 1.0;
          for (const auto& sphere : plan.spheres)
          {
            double in = 0.0, all = 0.0;
            for (const auto& d : plan.disk)
            {
              const double chord = std::sqrt(std::max(0.0, 1.0 - d[0] * d[0] - d[1] * d[1]));
              all += chord;
              in += sphere.t * dx + sphere.r * d[0] > a ? chord : 0.0;
            }
            open *= 1.0 - in / all;
            capOpen *= 1.0 - CapFraction(sphere.t * dx, sphere.r, a);
          }
          if (occupancy == cao::VCTOccupancy::Rays)
            open = 1.0 - caotest::HalfSpaceRayOcclusion(plan, c, a, plan.rayStep);
          occ += plan.coneWeights[c] * (1.0 - open);
          capOcc += plan.coneWeights[c] * (1.0 - capOpen);
        }
        exactAO = 1.0 - occ;
        const double ao = cao::ConeTraceAO(grid, plan, o, n);
        error2[fine] = std::fabs(ao - exactAO);
        std::printf("half-space x > %.1f, %4d slices, %zu spheres, %s: VCT AO %.4f, exact for its cones and "
                    "prisms %.4f (spheres' true volume: %.4f)\n",
          a, s.slices, plan.spheres.size(), cao::VCTOccupancyName(occupancy), ao, exactAO, 1.0 - capOcc);
      }
      CAO_CHECK(error2[1] < 0.01, "fine grid: |VCT - exact| = %.4f", error2[1]);
      CAO_CHECK(error2[0] > error2[1], "negative control: the coarse grid should be further (%.4f vs %.4f)",
        error2[0], error2[1]);
    }
  }
  // A thin roof (a closed slab half a voxel thick) at height H over P, n = +z:
  // every ray with cos(theta) > H / R meets it within R, so the reference
  // (cosine-weighted, binary within R) is (H / R)^2. The cones' rays stop at
  // the roof (within the six cones' coverage of the hemisphere: 0.1); the
  // paper's volume fraction counts the little of each sphere the roof fills
  // (the negative control: far lighter).
  {
    const double R = 0.5, H = 0.15, exact = (H / R) * (H / R);
    double ao[2] = { 0, 0 };
    for (cao::VCTOccupancy occupancy : { cao::VCTOccupancy::Rays, cao::VCTOccupancy::Volume })
    {
      cao::BitGrid grid;
      CAO_CHECK(cao::PlanGrid({ { -1, 1, -1, 1, -1, 1 } }, 0.0, 128, grid, error), "%s", error.c_str());
      std::vector<double> p;
      std::vector<std::int64_t> t;
      Box(-1, 1, p, t);
      for (std::size_t c = 2; c < p.size(); c += 3)
        p[c] = p[c] < 0 ? H : H + 0.5 * grid.voxel;
      CAO_CHECK(cao::FillGrid({ { &p, &t } }, grid, error), "%s", error.c_str());
      cao::VCTSettings s;
      s.radius = R;
      s.occupancy = occupancy;
      cao::VCTPlan plan;
      CAO_CHECK(cao::BuildVCTPlan(s, grid, plan, error), "%s", error.c_str());
      const double o[3] = { 0.003, -0.002, 0.0 }, n[3] = { 0, 0, 1 };
      ao[occupancy == cao::VCTOccupancy::Volume] = cao::ConeTraceAO(grid, plan, o, n);
    }
    std::printf("thin roof at H = 0.3 R: reference (H/R)^2 = %.4f; VCT rays %.4f, volume %.4f\n", exact, ao[0],
      ao[1]);
    CAO_CHECK(std::fabs(ao[0] - exact) < 0.1, "rays %.4f against %.4f", ao[0], exact);
    CAO_CHECK(ao[1] - exact > 0.3, "negative control: the volume fraction should under-occlude (%.4f)", ao[1]);
  }
  // An empty grid: AO 1 exactly; a point on a solid floor: open.
  {
    std::vector<double> p;
    std::vector<std::int64_t> t;
    Box(-1, 0, p, t);
    for (std::size_t c = 2; c < p.size(); c += 3)
      p[c] = p[c] == 0 ? 0.0 : -1.0; // floor z in [-1, 0]
    cao::BitGrid grid;
    CAO_CHECK(cao::VoxelizeWorld({ { &p, &t } }, { { -1, 0, -1, 0, -1, 0 } }, 0.5, 128, grid, error), "%s",
      error.c_str());
    cao::VCTSettings s;
    s.radius = 0.4;
    cao::VCTPlan plan;
    CAO_CHECK(cao::BuildVCTPlan(s, grid, plan, error), "%s", error.c_str());
    const double n[3] = { 0, 0, 1 }, onFloor[3] = { -0.5, -0.5, 0.0 }, above[3] = { -0.5, -0.5, 0.9 };
    const double floorAO = cao::ConeTraceAO(grid, plan, onFloor, n);
    const double freeAO = cao::ConeTraceAO(grid, plan, above, n);
    std::printf("a point on a solid floor: AO %.4f; far above it: %.4f\n", floorAO, freeAO);
    CAO_CHECK(freeAO == 1.0 && floorAO > 0.95, "floor %.4f free %.4f", floorAO, freeAO);
  }
  // The eye grid: the scene turned by R^T, in a grid whose frame is R.
  {
    std::vector<double> slab, ball;
    std::vector<std::int64_t> slabT, ballT;
    Box(-1.0, 1.0, slab, slabT);
    for (std::size_t c = 2; c < slab.size(); c += 3)
      slab[c] = slab[c] < 0 ? -0.3 : 0.0; // a slab z in [-0.3, 0]
    caotest::UVSphere(0.3, 48, ball, ballT);
    for (std::size_t c = 2; c < ball.size(); c += 3)
      ball[c] += 0.3; // resting on it
    const double a = 0.4, b = 0.7; // R: rotation about z by a, then about x by b
    const double rz[9] = { std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1 };
    const double rx[9] = { 1, 0, 0, 0, std::cos(b), -std::sin(b), 0, std::sin(b), std::cos(b) };
    std::array<double, 9> R{};
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 3; ++k)
          R[3 * r + c] += rx[3 * r + k] * rz[3 * k + c];
    auto turn = [](const std::array<double, 9>& m, bool transpose, const double* in, double* out) {
      for (int r = 0; r < 3; ++r)
        out[r] = transpose ? m[r] * in[0] + m[3 + r] * in[1] + m[6 + r] * in[2]
                           : m[3 * r] * in[0] + m[3 * r + 1] * in[1] + m[3 * r + 2] * in[2];
    };
    std::vector<double> slabR(slab.size()), ballR(ball.size());
    for (std::size_t i = 0; i < slab.size(); i += 3)
      turn(R, true, &slab[i], &slabR[i]);
    for (std::size_t i = 0; i < ball.size(); i += 3)
      turn(R, true, &ball[i], &ballR[i]);
    cao::BitGrid world, eye, wrongFrame;
    const std::vector<cao::MeshView> scene{ { &slab, &slabT }, { &ball, &ballT } };
    const std::vector<cao::MeshView> turned{ { &slabR, &slabT }, { &ballR, &ballT } };
    std::array<double, 9> Rt{};
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        Rt[3 * r + c] = R[3 * c + r];
    CAO_CHECK(cao::PlanEyeGrid(scene, { { 1, 0, 0, 0, 1, 0, 0, 0, 1 } }, 0.3, 128, world, error) &&
        cao::FillGrid(scene, world, error) && cao::PlanEyeGrid(turned, R, 0.3, 128, eye, error) &&
        cao::FillGrid(turned, eye, error) && cao::PlanEyeGrid(turned, Rt, 0.3, 128, wrongFrame, error) &&
        cao::FillGrid(turned, wrongFrame, error), "%s", error.c_str());
    cao::VCTSettings s;
    s.radius = 0.3;
    cao::VCTPlan planWorld, planEye, planWrong;
    CAO_CHECK(cao::BuildVCTPlan(s, world, planWorld, error) && cao::BuildVCTPlan(s, eye, planEye, error) &&
        cao::BuildVCTPlan(s, wrongFrame, planWrong, error), "%s", error.c_str());
    double worst = 0.0, wrongWorst = 0.0, darkest = 1.0;
    for (int k = 0; k < 200; ++k)
    {
      // Points on the slab's top around the contact, normal +z.
      const double r = 0.05 + 0.5 * (k % 20) / 20.0, phi = 2 * Pi * (k / 20) / 10.0 + 0.1;
      const double pt[3] = { r * std::cos(phi), r * std::sin(phi), 0.0 }, n[3] = { 0, 0, 1 };
      double ptR[3], nR[3];
      turn(R, true, pt, ptR);
      turn(R, true, n, nR);
      const double ao = cao::ConeTraceAO(world, planWorld, pt, n);
      darkest = std::min(darkest, ao);
      worst = std::max(worst, std::fabs(ao - cao::ConeTraceAO(eye, planEye, ptR, nR)));
      wrongWorst = std::max(wrongWorst, std::fabs(ao - cao::ConeTraceAO(wrongFrame, planWrong, ptR, nR)));
    }
    std::printf("eye grid (frame R, scene turned by R^T) vs world grid: max |dAO| %.2e over 200 points "
                "(darkest %.3f); the wrong frame: %.3f\n", worst, darkest, wrongWorst);
    CAO_CHECK(worst < 1e-9 && darkest < 0.8 && wrongWorst > 0.05, "eye grid: %g, wrong frame %g", worst,
      wrongWorst);
  }
  // InsideMask: a sphere under an anisotropic, shifted index map.
  {
    const int dims[3] = { 40, 30, 70 };
    const std::array<double, 12> toIndex{ { 1.0 / 0.035, 0, 0, 19.3, 0, 1.0 / 0.05, 0, 14.6, 0, 0,
      1.0 / 0.02, 35.2 } };
    std::vector<std::uint8_t> inside;
    CAO_CHECK(cao::InsideMask({ &sp, &st }, dims, toIndex, inside, error), "%s", error.c_str());
    const double sagitta = 0.6 * (1 - std::cos(Pi / 128)) * 2;
    std::int64_t wrong = 0, checked = 0, in = 0;
    for (int k = 0; k < dims[2]; ++k)
      for (int j = 0; j < dims[1]; ++j)
        for (int i = 0; i < dims[0]; ++i)
        {
          const double x = (i - 19.3) * 0.035, y = (j - 14.6) * 0.05, z = (k - 35.2) * 0.02;
          const double d = std::sqrt(x * x + y * y + z * z) - 0.6;
          if (std::fabs(d) <= sagitta + 1e-9)
            continue;
          ++checked;
          in += d < 0;
          wrong += (inside[i + dims[0] * (j + dims[1] * k)] != 0) != (d < 0);
        }
    std::printf("InsideMask, sphere r=0.6 on a 40x30x70 anisotropic grid: %lld of %lld wrong (%lld inside)\n",
      static_cast<long long>(wrong), static_cast<long long>(checked), static_cast<long long>(in));
    CAO_CHECK(wrong == 0 && in > 10000, "%lld wrong", static_cast<long long>(wrong));
    std::vector<std::int64_t> openT(st.begin(), st.end() - 3); // one triangle less: open
    CAO_CHECK(!cao::InsideMask({ &sp, &openT }, dims, toIndex, inside, error) &&
        error.find("open") != std::string::npos, "%s", error.c_str());
    // ShellMask, the same open sphere: every voxel it sets lies within a
    // voxel's diagonal (plus the sagitta) of the sphere (the shell spreads
    // each crossing over the slices its plane spans across a column's
    // width, then rounds to whole slices), and every
    // voxel the sphere passes through (its centre within 0.3 of a voxel of
    // the surface, away from the missing triangle) is set: a shell with no
    // gap, one voxel thick.
    std::vector<std::uint8_t> shell;
    CAO_CHECK(cao::ShellMask({ &sp, &openT }, dims, toIndex, shell, error), "%s", error.c_str());
    const double h[3] = { 0.035, 0.05, 0.02 };
    std::int64_t far = 0, missed = 0, set = 0;
    double farthest = 0.0;
    for (int k = 0; k < dims[2]; ++k)
      for (int j = 0; j < dims[1]; ++j)
        for (int i = 0; i < dims[0]; ++i)
        {
          const double x = (i - 19.3) * h[0], y = (j - 14.6) * h[1], z = (k - 35.2) * h[2];
          const double r = std::sqrt(x * x + y * y + z * z);
          const bool on = shell[i + dims[0] * (j + dims[1] * k)] != 0;
          set += on;
          // Distance to the surface in voxels along the radial direction.
          const double per = std::sqrt(x * x / (h[0] * h[0]) + y * y / (h[1] * h[1]) +
                                 z * z / (h[2] * h[2])) / std::max(r, 1e-12);
          const double voxels = std::fabs(r - 0.6) * per;
          far += on && voxels > std::sqrt(3.0) + sagitta * per + 1e-9;
          if (on)
            farthest = std::max(farthest, voxels);
          missed += !on && voxels < 0.3 && z < 0.5; // (the missing triangle is at the top pole)
        }
    std::printf("ShellMask, the open sphere: %lld voxels set, the farthest %.2f voxels from it, %lld "
                "farther than a diagonal, %lld on the surface missed\n",
      static_cast<long long>(set), farthest, static_cast<long long>(far), static_cast<long long>(missed));
    CAO_CHECK(far == 0 && missed == 0 && set > 1000, "far %lld, missed %lld", static_cast<long long>(far),
      static_cast<long long>(missed));
  }
  // The volume occludes: a homogeneous medium, no voxel near the point.
  {
    std::vector<double> p;
    std::vector<std::int64_t> t;
    Box(4.0, 4.1, p, t); // far away: the grid is empty around the origin
    cao::BitGrid grid;
    CAO_CHECK(cao::VoxelizeWorld({ { &p, &t } }, { { -1, 4.1, -1, 4.1, -1, 4.1 } }, 0.0, 256, grid, error),
      "%s", error.c_str());
    cao::OpacityVolume medium;
    medium.dims[0] = medium.dims[1] = medium.dims[2] = 11;
    medium.worldToIndex = { { 5, 0, 0, 5, 0, 5, 0, 5, 0, 0, 5, 5 } }; // [-1, 1]^3, spacing 0.2
    medium.unitDistance = 0.5;
    medium.alpha.assign(11 * 11 * 11, 0.3f);
    CAO_CHECK(medium.Validate().empty(), "%s", medium.Validate().c_str());
    cao::VCTSettings s;
    s.radius = 0.6;
    cao::VCTPlan plan;
    CAO_CHECK(cao::BuildVCTPlan(s, grid, plan, error), "%s", error.c_str());
    const double pt[3] = { 0.0, 0.0, 0.0 }, n[3] = { 0.0, 0.6, 0.8 };
    const double open = cao::ConeTraceAO(grid, plan, pt, n);
    plan.volumes.push_back(&medium);
    const double ao = cao::ConeTraceAO(grid, plan, pt, n);
    double diameters = 0.0;
    for (const auto& sphere : plan.spheres)
      diameters += 2.0 * sphere.r;
    const double expected = std::pow(1.0 - 0.3, diameters / 0.5);
    medium.alpha.assign(medium.alpha.size(), 0.0f); // carved away
    const double carved = cao::ConeTraceAO(grid, plan, pt, n);
    std::printf("homogeneous medium, opacity 0.3 per 0.5 units: AO %.6f (transmittance over %.4f units: %.6f); "
                "without the volume %.6f; carved %.6f\n", ao, diameters, expected, open, carved);
    CAO_CHECK(open == 1.0 && std::fabs(ao - expected) < 1e-6 && ao < 0.9 && carved == 1.0,
      "medium: %.6f vs %.6f, carved %.6f", ao, expected, carved);
    // A linear field is sampled exactly (trilinear), zero outside.
    for (int k = 0; k < 11; ++k)
      for (int j = 0; j < 11; ++j)
        for (int i = 0; i < 11; ++i)
          medium.alpha[i + 11 * (j + 11 * k)] = static_cast<float>(0.01 * i + 0.02 * j + 0.03 * k);
    const double q[3] = { 0.13, -0.27, 0.55 }, outside[3] = { 1.2, 0, 0 };
    const double linear = 0.01 * (5 * 0.13 + 5) + 0.02 * (5 * -0.27 + 5) + 0.03 * (5 * 0.55 + 5);
    CAO_CHECK(std::fabs(medium.Sample(q) - linear) < 1e-6 && medium.Sample(outside) == 0.0,
      "trilinear %.8f vs %.8f", medium.Sample(q), linear);
    medium.unitDistance = 0.0;
    CAO_CHECK(medium.Validate().find("unit distance") != std::string::npos, "%s", medium.Validate().c_str());
  }
  // The rays' march visits only the steps that can fall inside the grid:
  // with a radius 40 x the scene (the grid's padding capped at half its
  // diagonal) the AO of 4 000 cones equals the whole march's bit for bit,
  // from apexes inside and outside the grid, along the axes (zero
  // components) and in random directions. Negative control: the whole
  // march from the first sphere's near side (the start before the cap at
  // 3 voxels) differs.
  // Also with no padding at all, the box's faces on the grid's faces, where
  // a sample dropped at either end of the range would be seen.
  for (const double padding : { 1.05 * 40.0, 0.0 })
  {
    std::vector<double> p;
    std::vector<std::int64_t> t;
    Box(-0.5, 0.5, p, t);
    cao::BitGrid grid;
    std::string error;
    CAO_CHECK(cao::VoxelizeWorld({ { &p, &t } }, { { -0.5, 0.5, -0.5, 0.5, -0.5, 0.5 } }, padding, 64,
                grid, error),
      "%s", error.c_str());
    cao::VCTSettings s;
    s.radius = 40.0;
    s.slices = 64;
    cao::VCTPlan plan;
    CAO_CHECK(cao::BuildVCTPlan(s, grid, plan, error), "%s", error.c_str());
    CAO_CHECK(grid.voxel < 0.05, "the padding is capped: voxel %g", grid.voxel);
    auto whole = [&](const double* apex, const double* n, const double* dir, const double* u,
                   const double* v, double rayStep, bool capped) {
      const double inv = 1.0 / grid.voxel;
      const cao::VCTPlan::Sphere& first = plan.spheres.front();
      const double nearSide = first.t - first.r;
      const double t0 = capped ? std::min(nearSide, 3.0 * grid.voxel) : nearSide;
      const double t1 = plan.spheres.back().t + plan.spheres.back().r;
      double blocked = 0.0, all = 0.0;
      for (const auto& sample : plan.disk)
      {
        double ray[3];
        for (int d = 0; d < 3; ++d)
          ray[d] = dir[d] + plan.coneTangent * (sample[0] * u[d] + sample[1] * v[d]);
        const double length = std::sqrt(ray[0] * ray[0] + ray[1] * ray[1] + ray[2] * ray[2]);
        const double weight = std::max(0.0, (ray[0] * n[0] + ray[1] * n[1] + ray[2] * n[2]) / length);
        all += weight;
        const int steps = std::max(1, static_cast<int>(std::ceil((t1 - t0) * length / rayStep)));
        const double step = (t1 - t0) / steps;
        for (int m = 0; m < steps; ++m)
        {
          const double tau = t0 + (m + 0.5) * step;
          int ijk[3];
          for (int d = 0; d < 3; ++d)
            ijk[d] = static_cast<int>(std::floor((apex[d] + tau * ray[d] - grid.origin[d]) * inv));
          if (ijk[0] >= 0 && ijk[1] >= 0 && ijk[2] >= 0 && ijk[0] < grid.nx && ijk[1] < grid.ny &&
            ijk[2] < grid.slices && grid.Bit(ijk[0], ijk[1], ijk[2]))
          {
            blocked += weight;
            break;
          }
        }
      }
      return all > 0.0 ? blocked / all : 0.0;
    };
    std::uint64_t state = 12345;
    auto uniform = [&state]() {
      state = state * 6364136223846793005ull + 1442695040888963407ull;
      return static_cast<double>(state >> 11) * (1.0 / 9007199254740992.0);
    };
    int mismatches = 0, previousDiffers = 0, occluded = 0;
    const double extent = grid.nx * grid.voxel; // the grid's width
    for (int k = 0; k < 4000; ++k)
    {
      double apex[3], dir[3];
      for (int d = 0; d < 3; ++d)
        apex[d] = (uniform() - 0.5) * 1.6 * extent;
      if (k % 4 == 0) // along an axis: two zero components
      {
        dir[0] = dir[1] = dir[2] = 0.0;
        dir[k / 4 % 3] = (k / 12) % 2 ? 1.0 : -1.0;
      }
      else
      {
        const double z = 2.0 * uniform() - 1.0, phi = 2.0 * Pi * uniform();
        const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
        dir[0] = r * std::cos(phi);
        dir[1] = r * std::sin(phi);
        dir[2] = z;
      }
      const double a[3] = { std::fabs(dir[0]) < 0.6 ? 1.0 : 0.0, std::fabs(dir[0]) < 0.6 ? 0.0 : 1.0, 0.0 };
      double u[3] = { a[1] * dir[2] - a[2] * dir[1], a[2] * dir[0] - a[0] * dir[2], a[0] * dir[1] - a[1] * dir[0] };
      const double lu = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
      for (double& x : u)
        x /= lu;
      const double v[3] = { dir[1] * u[2] - dir[2] * u[1], dir[2] * u[0] - dir[0] * u[2],
        dir[0] * u[1] - dir[1] * u[0] };
      const double got = cao::RayOcclusion(grid, plan, apex, dir, dir, u, v, plan.rayStep);
      const double expected = whole(apex, dir, dir, u, v, plan.rayStep, true);
      mismatches += got != expected;
      previousDiffers += whole(apex, dir, dir, u, v, plan.rayStep, false) != expected;
      occluded += expected > 0.0;
    }
    std::printf("march within the grid (padding %g): %d of 4000 cones differ from the whole march "
                "(%d occluded); the previous start differs at %d\n",
      padding, mismatches, occluded, previousDiffers);
    CAO_CHECK(mismatches == 0, "the march within the grid differs from the whole march at %d cones", mismatches);
    CAO_CHECK(occluded > 200 && previousDiffers > 0,
      "the cases are not telling: %d occluded, the previous start differs at %d", occluded, previousDiffers);
  }

  // Bands: a wall standing on a floor, seen obliquely. With one ray set for
  // every pixel, each ray's hit or miss is a step in the floor's AO, and
  // the steps are contour bands around the wall; the 4 x 4 pattern and its
  // filter (VCTSettings::interleave, the default) average 16 turned sets.
  // Measured: the RMS second difference of the AO along rows and columns
  // of floor pixels (the bench's ripple), against the reference's own (its
  // two seeds' product: its noise averages out). Negative control: the
  // pattern off.
  {
    caotest::TriangleScene floorAndWall;
    floorAndWall.Box(-3, 3, -3, 3, -0.5, 0);
    floorAndWall.Box(-0.15, 0.15, -2, 2, 0, 2);
    cao::TriangleBVH bvh;
    CAO_CHECK(bvh.Build(floorAndWall.points, floorAndWall.tris, error), "%s", error.c_str());
    const double eye[3] = { 4.0, -4.5, 5.0 }, at[3] = { 0.3, 0, 0 };
    cao::SurfaceFrame frame;
    CAO_CHECK(cao::CastPrimary(bvh, caotest::LookAt(160, 120, eye, at, 40, 0.1, 30), frame, error), "%s",
      error.c_str());
    const double radius = 1.2;
    cao::BitGrid grid;
    CAO_CHECK(cao::VoxelizeWorld({ { &floorAndWall.points, &floorAndWall.tris } }, bvh.Bounds(), 1.05 * radius, 256,
      grid, error), "%s", error.c_str());
    // Floor pixels whose row or column neighbours are floor too (z = 0,
    // normal +z), away from the wall's foot.
    std::vector<std::array<std::int64_t, 2>> flat;
    const std::size_t w = static_cast<std::size_t>(frame.width);
    auto floorPixel = [&](std::size_t k) {
      return frame.triangle[k] >= 0 && std::fabs(frame.position[3 * k + 2]) < 1e-9 &&
        frame.normal[3 * k + 2] > 0.999 && std::fabs(frame.position[3 * k]) > 0.3;
    };
    for (std::size_t j = 1; j + 1 < static_cast<std::size_t>(frame.height); ++j)
      for (std::size_t i = 1; i + 1 < w; ++i)
        for (std::size_t step : { std::size_t(1), w })
        {
          const std::size_t k = j * w + i;
          if (floorPixel(k) && floorPixel(k - step) && floorPixel(k + step))
            flat.push_back({ static_cast<std::int64_t>(k), static_cast<std::int64_t>(step) });
        }
    cao::SurfaceFrame reference = frame, second = frame;
    cao::AOReferenceSettings rs;
    rs.radius = radius;
    rs.rays = 1024;
    CAO_CHECK(cao::ReferenceFrame(bvh, rs, reference, error), "%s", error.c_str());
    rs.seed = 2;
    CAO_CHECK(cao::ReferenceFrame(bvh, rs, second, error), "%s", error.c_str());
    double rms[2] = { 0, 0 }, rmse[2] = { 0, 0 };
    for (int on = 0; on < 2; ++on)
    {
      cao::VCTSettings vs;
      vs.radius = radius;
      vs.slices = 256;
      vs.interleave = on == 1;
      cao::VCTPlan plan;
      cao::SurfaceFrame f = frame;
      CAO_CHECK(cao::BuildVCTPlan(vs, grid, plan, error) && cao::VCTFrame(grid, plan, f, 0, error), "%s",
        error.c_str());
      rms[on] = cao::Ripple(flat, f.ao);
      double sum = 0;
      std::size_t n = 0;
      for (std::size_t k = 0; k < f.ao.size(); ++k)
        if (frame.triangle[k] >= 0)
        {
          sum += (f.ao[k] - reference.ao[k]) * (f.ao[k] - reference.ao[k]);
          ++n;
        }
      rmse[on] = std::sqrt(sum / std::max<std::size_t>(n, 1));
    }
    const double own = cao::Ripple(flat, reference.ao, &second.ao);
    std::printf("bands on a floor beside a wall (%zu pixel triples): ripple %.5f with the 4 x 4 pattern, %.5f "
                "without (negative control), the reference's own %.5f; RMSE %.4f and %.4f\n",
      flat.size(), rms[1], rms[0], own, rmse[1], rmse[0]);
    CAO_CHECK(flat.size() > 3000, "too few floor pixels (%zu)", flat.size());
    // (Measured 1.75 x: what is left is the shape of six cones' profile
    // across the wall's shadow, smooth in the picture, not steps: the ray
    // samples jittered per pixel as well changed it by 2%.)
    CAO_CHECK(rms[1] <= 2.0 * own, "the pattern's ripple %.5f exceeds 2 x the reference's %.5f", rms[1], own);
    CAO_CHECK(rms[0] > 3.0 * rms[1], "negative control: without the pattern the bands should show (%.5f vs %.5f)",
      rms[0], rms[1]);
    CAO_CHECK(rmse[1] <= rmse[0], "the pattern should not add error (RMSE %.4f vs %.4f)", rmse[1], rmse[0]);
  }

  // Bad input.
  {
    cao::VCTSettings s;
    s.filterTolerance = 0.0;
    CAO_CHECK(s.Validate().find("filter tolerance") != std::string::npos, "%s", s.Validate().c_str());
    s.filterTolerance = 0.1;
    s.slices = 100;
    CAO_CHECK(s.Validate().find("multiple of 32") != std::string::npos, "%s", s.Validate().c_str());
    s.slices = 128;
    s.quality = cao::Quality::Custom;
    s.prisms = 0;
    CAO_CHECK(s.Validate().find("prisms") != std::string::npos, "%s", s.Validate().c_str());
    std::vector<double> p = { 0, 0, 0, 1, 0, 0, 0, 1, 0 };
    std::vector<std::int64_t> t = { 0, 1, 5 };
    cao::BitGrid grid;
    CAO_CHECK(!cao::VoxelizeWorld({ { &p, &t } }, { { 0, 1, 0, 1, 0, 1 } }, 0, 128, grid, error) &&
        error.find("point 5 of 3") != std::string::npos, "%s", error.c_str());
    CAO_CHECK(!cao::VoxelizeWorld({}, { { 0, 1, 0, 1, 0, 1 } }, 0, 48, grid, error) &&
        error.find("multiple of 32") != std::string::npos, "%s", error.c_str());
  }
  return 0;
}
