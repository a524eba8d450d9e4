/**
 * caoSurfaceLines — `cao surface` on lines (polylines, streamlines): each
 * line is a tube of radius --tube-radius, seen by the same fitted camera
 * as meshes are, its AO by line AO (Benevides 2015's line voxelization and prism
 * sampling, Kernels/Lines), the ray-traced reference on the exact tubes
 * (capsules), vtkSSAOPass on the tubes as vtkTubeFilter draws them, or
 * none. The pieces are shared with `cao bench lines`.
 */
#ifndef caoSurfaceLines_h
#define caoSurfaceLines_h

#include "caoSurface.h"

#include "caoCapsules.h"
#include "caoLineAO.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace caocli
{
/// Lines read from polygonal files: their segments, as capsules of the tube
/// radius (the G-buffer and the reference), and as tube meshes (VTK's
/// renderers).
struct LineScene
{
  cao::LineSegments lines;
  cao::CapsuleBVH capsules;
  SurfaceScene tubes; ///< made by MakeTubes
  std::vector<vtkSmartPointer<vtkPolyData>> read;
  std::vector<std::string> paths;
  std::vector<std::int64_t> segmentLine; ///< each segment's polyline (0, 1, ... over the files)
  std::int64_t polylines = 0;
  double tubeRadius = 0.0, diagonal = 0.0;
  std::array<double, 6> bounds{ { 1, -1, 1, -1, 1, -1 } }; ///< the tubes'
  /// The lines of `read` (each file's polylines; polygons are refused) as
  /// tubes of `tubeRadius` (0: DefaultTubeRadius of their bounds).
  bool Load(const std::vector<std::string>& files, const std::vector<vtkSmartPointer<vtkPolyData>>& read,
    double tubeRadius, std::string& error);
  /// The tubes as triangle meshes (vtkTubeFilter, 16 sides, capped) in `tubes`.
  bool MakeTubes(std::string& error);
  /// The default AO radius of the tubes (cao::DefaultAORadius over their area).
  double DefaultRadius() const;
  /// The tubes' side area (2 pi r x the lines' length).
  double TubeArea() const;
};

/// The default tube radius: 1/200 of the lines' bounding-box diagonal.
constexpr double DefaultTubeFraction = 0.005;

/// `x` as a message shows a number (6 significant digits).
std::string Compact(double x);
/// The mean of `count` values summing to `sum`, or `none` (JSON null, or
/// "n/a") when there is none: a mean of no pixel is not an AO of 0.
std::string MeanText(std::int64_t count, double sum, const char* none, int digits = 10);

/// Whether `mesh` is a line input: lines and no polygons or strips (a mesh
/// with feature edges or outlines among its cells is a mesh: its lines are
/// ignored, as before lines were supported).
bool IsLineInput(vtkPolyData* mesh);
/// Whether any of `read` is a line input (then `cao surface` draws lines).
bool HasLines(const std::vector<vtkSmartPointer<vtkPolyData>>& read);

/// The camera's right and up directions (its view matrix's first rows).
void CameraAxes(vtkCamera* camera, double right[3], double up[3]);

/// What `cao surface` says for lines.
struct LineJob
{
  std::string method, output, window;
  SurfaceView view;
  double radius = 0.0; ///< 0: the default
  double tubeRadius = 0.0;
  cao::LineAOSettings lineAO;
  cao::AOReferenceSettings reference;
  cao::VCTSettings vct; ///< the meshes' voxel cones, when meshes come with the lines
  int kernel = 32, threads = 0;
  std::string backend = "auto"; ///< line AO's prisms: auto, cpu or gl (the grid and G-buffer: the CPU)
  bool aoOnly = false, json = false;
};

/// `cao surface` on the lines of `read` (HasLines), with the meshes among
/// them occluding the lines and occluded by them in the same frame (one
/// grid: line AO for the lines, voxel cones for the meshes; or the
/// reference over both, or vtkSSAOPass over both): the exit code.
int RunSurfaceLines(LineJob& job, const std::vector<std::string>& files,
  const std::vector<vtkSmartPointer<vtkPolyData>>& read);
}

#endif
