// caoSceneGrid.h - the scene's voxel grid, shared by every kind of
// geometry and every technique that reads it (voxel cone tracing on the
// surfaces, the volumes and lines that occlude through it): meshes
// rasterized into a planned cao::BitGrid (a world grid, an eye grid in the
// camera's axes, or the paper's frustum grid of a column per pixel; Dalla
// Favera and Celes Sec. III-A and III-B), their open edges, a closed mesh's
// inside on a regular grid, and a volume's opacity as the grid's readers
// sample it.
//
// Voxelization: the meshes are rasterized along the grid's z axis, one
// column per (x, y) voxel centre, with the top-left rule of a GPU
// rasterizer (so that a column through a shared edge or vertex counts one
// crossing, and the CPU and GPU grids can agree bit for bit). A closed mesh
// XORs, at each crossing, every slice whose centre lies beyond it (solid
// voxelization: odd parity is inside). A mesh with boundary edges (open) is
// voxelized as a shell (each crossing sets its own slice) and reported. By
// default a closed mesh's crossings set their own slices too (parity plus
// surface: a wall thinner than a voxel keeps its voxels). The meshes are
// filled one by one and OR'ed, so that overlapping closed meshes stay
// solid.
#ifndef caoSceneGrid_h
#define caoSceneGrid_h

#include "caoBitGrid.h"
#include "caoPixelCamera.h"
#include "caoSurfaceFrame.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace cao
{

/// One mesh to voxelize: points (x, y, z) and triangles (3 ids each).
struct MeshView
{
  const std::vector<double>* points = nullptr;
  const std::vector<std::int64_t>* triangles = nullptr;
  /// Its OpenEdges when the caller knows them (a mesh voxelized again and
  /// again, as a frustum grid's at every camera change); -1: counted by
  /// the voxelizer.
  std::int64_t openEdges = -1;
};

/// The number of edges of a triangle mesh used by exactly one triangle
/// (0: closed; edges used by 3 or more count as well, as non-manifold).
std::int64_t OpenEdges(const MeshView& mesh);
/// The same, and those edges in `edges`: 7 numbers each, the two ends'
/// coordinates (the lexicographically smaller first) and the triangles
/// using it, so that the pieces of one mesh can be matched up (an edge
/// whose uses over all pieces add up to 2 is not open).
std::int64_t OpenEdges(const MeshView& mesh, std::vector<double>& edges);
/// How many edges of `edges` (OpenEdges' records of several pieces, in any
/// order) are open when their uses are added up over the pieces; ends
/// within `tolerance` (rounded to its multiples) are one point, since
/// pieces made apart may place a shared point a rounding apart.
std::int64_t OpenEdgesOfPieces(std::vector<double> edges, double tolerance);

/// Voxelizes `meshes` into a grid around `bounds` (xmin, xmax, ...) padded
/// by `padding` on every side, with `slices` slices along z and cubic
/// voxels (h = the padded box's largest side / slices). With
/// `surfaceVoxels` a closed mesh also sets the slice of each crossing (the
/// voxels its surface passes through along z), so that a wall thinner than
/// a voxel, whose parity leaves no voxel centre inside, still occludes.
/// False with the reason on bad input or a grid of more than
/// MaximumColumns columns.
bool VoxelizeWorld(const std::vector<MeshView>& meshes, const std::array<double, 6>& bounds,
  double padding, int slices, BitGrid& grid, std::string& error, bool surfaceVoxels = true);

/// Rasterizes `meshes` into `grid` as planned (PlanGrid, PlanEyeGrid or PlanFrustumGrid;
/// its bits are replaced): what VoxelizeWorld does after planning.
bool FillGrid(const std::vector<MeshView>& meshes, BitGrid& grid, std::string& error,
  bool surfaceVoxels = true);

/// One mesh's (or one piece of a mesh's) bits in a planned world or eye
/// grid's columns, accumulated into the vectors given (sized to the grid's
/// words when empty; null: not made): `parity` XOR-filled from each
/// crossing to the column's top, as a closed mesh's inside is (the pieces
/// of a mesh XOR into the whole mesh's), `surface` each crossing's own
/// slice, `shell` what an open mesh leaves (the slices its plane spans over
/// a column's width around each crossing). FillGrid's rasterization, for
/// grids combined from pieces (several processes' pieces of one scene).
bool PieceBits(const MeshView& mesh, const BitGrid& grid, std::vector<std::uint32_t>* parity,
  std::vector<std::uint32_t>* surface, std::vector<std::uint32_t>* shell, std::string& error);

/// Whether `parity` (PieceBits' of a mesh's pieces, XOR-ed) is a closed
/// surface's as the grid sees it: every column crossed an even number of
/// times, so its last slice (padding beyond the meshes) is clear.
bool ParityClosed(const BitGrid& grid, const std::vector<std::uint32_t>& parity);

/// An eye grid's plan: the meshes' bounds in the frame `axes`, padded, as
/// PlanGrid plans a world grid (bits empty).
bool PlanEyeGrid(const std::vector<MeshView>& meshes, const std::array<double, 9>& axes,
  double padding, int slices, BitGrid& grid, std::string& error);
/// The meshes' bounds in the frame `axes` (min > max: no points), as
/// PlanEyeGrid takes them; PlanGrid of several processes' bounds together,
/// with grid.axes = axes, is the eye grid of all their meshes.
bool EyeBounds(const std::vector<MeshView>& meshes, const std::array<double, 9>& axes,
  std::array<double, 6>& bounds, std::string& error);

/// The paper's eye-space grid for `camera` (Dalla Favera and Celes, Sec. III-B and Eq. 2):
/// a column per pixel (under a perspective camera the columns fan out with
/// the pixels' rays), `slices` slices per column, linear in depth from the
/// column's visible depth in `frame` (its z_nearest: Eisemann's local
/// slice map; uncovered pixels, or all with a null `frame`, the meshes'
/// nearest depth: the paper's Fig. 4 (a)) to the meshes' farthest depth
/// plus one slice. Depends on the camera and the G-buffer: rebuilt with
/// every camera change. No mesh in front of the camera: an empty grid.
/// FillGrid rasterizes it in screen space (1 / w
/// interpolated, perspective-correct), with the parity counted from beyond
/// the far depth, so that a camera inside a closed mesh or a mesh cut by
/// the eye plane keeps a right inside. At most MaximumFrustumBytes of bits.
bool PlanFrustumGrid(const std::vector<MeshView>& meshes, const PixelCamera& camera,
  const SurfaceFrame* frame, int slices, BitGrid& grid, std::string& error);
/// Empty when a frustum grid of width x height pixels and `slices` slices
/// fits the limits (MaximumColumns columns, MaximumFrustumBytes of bits),
/// else why not, with the limit: PlanFrustumGrid's check, to be made
/// before the G-buffer is cast.
std::string CheckFrustumSize(int width, int height, int slices);

/// A mesh's triangles as a frustum grid's rasterizer sees them (the CPU's
/// and the GPU's): per vertex pixel x, y and a key linear in screen space
/// (1 / w under a perspective camera, NDC z under a parallel one), three
/// vertices per triangle, clipped at the eye plane (a cut triangle may give
/// two). False when `grid` is not a frustum grid or the mesh is empty.
bool FrustumScreenTriangles(const BitGrid& grid, const MeshView& mesh, std::vector<double>& soup);

/// Which voxel centres of a regular grid lie inside a closed mesh, by the
/// voxelizer's parity (top-left rule along the grid's k axis): inside[i +
/// dims0 * (j + dims1 * k)] = 1. `worldToIndex` (3 x 4, row-major) maps the
/// mesh's points to continuous voxel indices (voxel centres at integers).
/// False with the reason when the mesh is open or has bad coordinates, or
/// the grid is empty or has more than 2^31 voxels.
bool InsideMask(const MeshView& mesh, const int dims[3], const std::array<double, 12>& worldToIndex,
  std::vector<std::uint8_t>& inside, std::string& error);

/// Which voxels of a regular grid an open surface passes through: the
/// union of its shells (RasterizeColumns' open-mesh shell: at each column
/// crossing the slices the triangle's plane spans over a column's width)
/// along each of the grid's three axes, so that every triangle is
/// rasterized along the axis it faces most and a wall edge-on to one axis
/// is still voxelized. mask[i + dims0 * (j + dims1 * k)] = 1, as InsideMask.
/// For occluders that enclose no inside (an isosurface cut by the volume's
/// box, ParaView's tubes, whose caps share no points with the sides).
bool ShellMask(const MeshView& mesh, const int dims[3], const std::array<double, 12>& worldToIndex,
  std::vector<std::uint8_t>& mask, std::string& error);

/// A volume's opacity as the cones read it (the volume occludes surfaces):
/// per voxel the opacity of `unitDistance` world units of it (VTK's scalar
/// opacity and its unit distance), clipped voxels 0. Along a cone, a
/// sphere of radius r sees the mean opacity a of the volume at its centre
/// and its prisms' points (on the sphere's disk across the grid's z axis,
/// where the bits are counted), over its diameter: 1 - (1 - a)^(2r / unit), the
/// step-length correction LAO uses (Titov et al. Eq. 2, Dalla Favera and Celes Sec. III-C2:
/// one absorption model), composed with the sphere's voxel occupancy as
/// 1 - (1 - occ)(1 - alpha) (occupancy "volume"), or with the cone's rays'
/// occlusion as 1 - (1 - occ_rays) prod_k (1 - alpha_k) ("rays").
struct OpacityVolume
{
  int dims[3] = { 0, 0, 0 };
  std::array<double, 12> worldToIndex{ { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0 } }; ///< 3 x 4
  std::vector<float> alpha; ///< i + dims0 * (j + dims1 * k)
  double unitDistance = 1.0;
  /// Trilinear opacity at a world point; 0 outside the grid.
  double Sample(const double world[3]) const;
  /// Empty when usable, else why not.
  std::string Validate() const;
};



/// A mesh's points in the grid's units, (p - origin) / voxel, as the
/// voxelizer (CPU or GPU) rasterizes them. False on a NaN or infinity. A
/// frustum grid's points go through FrustumScreenTriangles instead: for it
/// the check alone, `out` empty.
bool GridPoints(const BitGrid& grid, const std::vector<double>& points, std::vector<double>& out,
  std::string& error);

}

#endif
