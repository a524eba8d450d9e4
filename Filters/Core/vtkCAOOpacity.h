/**
 * vtkCAOOpacity — private glue: the LAO's opacity volume from scalars and a
 * transfer function, step-corrected. Shared by vtkLocalAmbientOcclusion and
 * the contextual-AO volume mapper, so that both compute the same opacity
 * (and so the same AO) from the same function. Not wrapped or installed.
 */
#ifndef vtkCAOOpacity_h
#define vtkCAOOpacity_h

#include "caoFiltersCoreModule.h" // For export macro

#include <cstdint>
#include <string>
#include <vector>

class vtkAlgorithm;
class vtkDataArray;
class vtkImageData;
class vtkMatrix4x4;
class vtkPolyData;
class vtkPiecewiseFunction;

namespace vtkCAO
{
/**
 * Evaluate `tf` for every voxel of `scalars` (component `component`),
 * corrected for samples `stepOverUnit` unit distances apart. Integer
 * arrays with at most 65536 distinct values use an exact table. NaN/Inf
 * scalars become transparent and are counted in `nonFinite`. A null `tf`
 * is a ramp from 0 at the scalars' smallest value to 1 at the largest. Progress goes
 * from 0 to 0.1 on `self` (may be null); false when aborted.
 *
 * With `changed` (a byte per voxel), `opacity` holds the previous opacity
 * and is written over in place: changed[i] says whether voxel i's new value
 * differs from it by bit pattern (as the LAO march reads them: -0 and 0, or
 * two NaNs, differ), the opacity edit's mask without a second array.
 */
CAOFILTERSCORE_EXPORT bool ComputeOpacity(vtkAlgorithm* self, vtkDataArray* scalars, int component,
  vtkPiecewiseFunction* tf, double stepOverUnit, float* opacity, std::int64_t& nonFinite,
  std::uint8_t* changed = nullptr);

/**
 * Whether a warning about `count` NaN (or infinite) values of `scalars`
 * (component `component`) says something new: the scalars (identity,
 * modification time), the component or the count differ from the last
 * said. A filter or mapper that runs again over the same scalars (an edit
 * of the opacity map) does not repeat it; a count of 0 forgets.
 */
struct NonFiniteNote
{
  bool Changed(const vtkDataArray* scalars, int component, std::int64_t count);

private:
  const vtkDataArray* Scalars = nullptr;
  unsigned long Time = 0; // (vtkMTimeType)
  int Component = -1;
  std::int64_t Count = 0;
};

/**
 * Opaque meshes in a volume's opacity: every voxel of `grid` whose centre
 * lies inside one of `meshes` (closed triangle meshes, polygons
 * triangulated, in the grid's physical coordinates) gets opacity 1, an
 * opaque solid at any sample step (the voxelizer's parity along the grid's
 * k axis: cao::InsideMask); an open triangle mesh (an isosurface cut by the
 * volume's box; ParaView's tubes, whose caps share no points with their
 * sides) makes opaque the voxels its surface passes through (its shell
 * along the three axes: cao::ShellMask), counted in `surfaces` when given;
 * a mesh with lines and no polygons (streamlines) makes opaque the voxels
 * its segments pass through (their supercover: cao::VoxelizeLines on the
 * volume's voxels). `occupied` counts those voxels (each once).
 * A mesh with no points (an isosurface whose value leaves the data's
 * range) occludes nothing. False with the reason, naming the mesh, when a
 * mesh has points but no polygons nor lines, or has non-finite points, or the grid's index-to-physical
 * matrix is singular; `opacity` is then unchanged. `poses[m]`, when given
 * and not null, maps mesh m's points to the grid's physical coordinates
 * (no copy of the mesh is made).
 */
CAOFILTERSCORE_EXPORT bool OccludeOpacity(vtkImageData* grid, const std::vector<vtkPolyData*>& meshes,
  float* opacity, std::int64_t& occupied, std::string& error,
  const std::vector<vtkMatrix4x4*>& poses = {}, int* surfaces = nullptr);
}

#endif
