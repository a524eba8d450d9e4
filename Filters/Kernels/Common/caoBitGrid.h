// caoBitGrid.h - the bit grid every kind voxelizes into and reads from
// (surfaces' voxel cone tracing, lines' prism sampling): columns of bits,
// 32 slices per word, in a world, eye or frustum frame.
#ifndef caoBitGrid_h
#define caoBitGrid_h

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace cao
{

/// A world-space bit grid: column (i, j) at x = origin[0] + (i + 1/2) h,
/// y = origin[1] + (j + 1/2) h holds `slices` bits, slice k at
/// z = origin[2] + (k + 1/2) h; 32 slices per word, slice 0 in bit 0 of
/// word 0.
struct BitGrid
{
  int nx = 0, ny = 0, slices = 0, words = 0;
  std::array<double, 3> origin{ { 0, 0, 0 } };
  double voxel = 1.0;
  /// The grid's frame: row r is the grid's axis r in world coordinates
  /// (identity: a world grid; an eye grid's rows are the camera's right, up
  /// and backward directions, so that its slices are depth slices, as in
  /// the paper). Points enter the grid as axes * p (ToGrid).
  std::array<double, 9> axes{ { 1, 0, 0, 0, 1, 0, 0, 0, 1 } };
  void ToGrid(const double world[3], double out[3]) const;
  void ToWorld(const double grid[3], double out[3]) const;
  /// The frustum grid (PlanFrustumGrid; Dalla Favera and Celes Sec. III-B, the paper's
  /// eye-space grid): column (i, j) is the ray of pixel (i, j), slice k of
  /// a column spans depths [near + k step, near + (k + 1) step), step =
  /// (far - near) / slices, `near` the column's own (its pixel's visible
  /// depth: the paper's z_nearest). The depth is the clip w (eye depth)
  /// under a perspective camera, NDC z under a parallel one. Points enter
  /// it in the grid frame (ToGrid: `axes` are the camera's right, up and
  /// backward) and are mapped by `toClip`; origin and voxel are unused
  /// there but `voxel` (a representative voxel: the smaller of a pixel's
  /// width and a slice at the median visible depth) sets the plan's
  /// smallest sphere. Off (empty toClip) for world and eye grids.
  struct Frustum
  {
    bool perspective = true;
    std::array<double, 16> toClip{};      ///< grid frame -> clip, row-major
    std::vector<double> nearDepth;        ///< per column (j * nx + i)
    std::vector<double> slicesPerDepth;   ///< per column: slices / (far - near)
    double farDepth = 0.0;
    double worldPerDepth = 1.0;           ///< world length of one unit of depth along the view
    double medianPixel = 0.0, medianSlice = 0.0; ///< world sizes at the median visible depth
    /// An open mesh's shell is a pixel deep, not a slice: its slices at a
    /// crossing of depth d are ceil((perspective ? d : 1) * shellScale *
    /// slicesPerDepth) (a pixel's width over a slice's depth there).
    double shellScale = 0.0;
  };
  Frustum frustum;
  bool IsFrustum() const { return !this->frustum.nearDepth.empty(); }
  /// A frustum grid's cell of grid-frame point q: column (i, j) and slice
  /// coordinate s (slice k spans [k, k + 1)); false outside its columns
  /// or behind the eye.
  bool FrustumCell(const double q[3], int& i, int& j, double& s) const;
  /// A frustum grid's voxel at grid-frame point q in world units: the
  /// smaller (or `larger`) of a pixel's width there and its column's slice.
  double FrustumVoxel(const double q[3], bool larger = false) const;
  static constexpr std::int64_t MaximumFrustumBytes = std::int64_t(1) << 30;
  std::vector<std::uint32_t> bits; ///< (j * nx + i) * words + word
  std::vector<std::int64_t> openEdges; ///< per mesh, as voxelized (0: solid fill)
  static constexpr std::int64_t MaximumColumns = std::int64_t(4096) * 4096;

  bool Bit(int i, int j, int k) const
  {
    return (this->bits[(static_cast<std::size_t>(j) * this->nx + i) * this->words + (k >> 5)] >> (k & 31)) & 1u;
  }
  /// Set bits in slices [k0, k1] of column (i, j) (clamped; 0 if outside).
  int CountBits(int i, int j, int k0, int k1) const;
  std::int64_t CountAll() const;
};

/// The frame of an eye grid: the rows of a camera's view matrix (right, up,
/// backward), orthonormalised. False if they are degenerate.
bool EyeAxes(const double right[3], const double up[3], std::array<double, 9>& axes,
  std::string& error);

/// A world or eye grid's plan around `bounds`, as VoxelizeWorld makes it,
/// without its bits (size, origin, voxel; bits
/// empty): what the GPU voxelizer fills.
bool PlanGrid(const std::array<double, 6>& bounds, double padding, int slices, BitGrid& grid,
  std::string& error);
/// A frustum grid's clip coordinates of grid-frame point q (m: its
/// frustum.toClip).
inline void GridToClip(const std::array<double, 16>& m, const double q[3], double c[4])
{
  for (int r = 0; r < 4; ++r)
    c[r] = m[4 * r] * q[0] + m[4 * r + 1] * q[1] + m[4 * r + 2] * q[2] + m[4 * r + 3];
}

}

#endif
