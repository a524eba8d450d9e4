/**
 * vtkCAOSceneExchange — what the processes that render one scene together
 * (parallel rendering: each draws its own pieces, the images composited by
 * depth) agree on for the surface AO: whether any process's scene changed
 * this frame, the bounds of every process's pieces together, and the grid
 * combined from every process's voxels (per actor its pieces' parities
 * XOR-ed, then the processes' grids OR-ed). Every call here is collective:
 * every process calls Frame at every frame, and the others in the same
 * order whenever Frame says a scene changed, whatever it holds (no
 * pieces, a failed voxelization: zeros).
 */
#ifndef vtkCAOSceneExchange_h
#define vtkCAOSceneExchange_h

#include "caoRenderingSceneModule.h" // For export macro

#include "caoVoxelConeTracing.h" // For cao::BitGrid

#include <array>      // For the bounds
#include <cstdint>    // For the words
#include <functional> // For the local bounds
#include <vector>     // For the key

class vtkMultiProcessController;

namespace vtkCAO
{
class CAORENDERINGSCENE_EXPORT SceneExchange
{
public:
  /// One frame: this process's scene `key`; `localBounds` is asked for
  /// (xmin, xmax, ymin, ymax, zmin, zmax; min > max when empty) only when
  /// the key changed. True when any process's key changed this frame.
  bool Frame(vtkMultiProcessController* controller, const std::vector<double>& key,
    const std::function<std::array<double, 6>()>& localBounds);
  /// Every process's pieces' bounds together (min > max: none has any).
  const std::array<double, 6>& Bounds() const { return this->Common; }
  bool HasBounds() const { return this->Common[0] <= this->Common[1]; }
  /// `grid` (planned from Bounds(); its bits this process's voxels, or none
  /// when it has nothing or failed: taken as zeros) becomes the OR of every
  /// process's bits. False when the exchange failed.
  bool OrGrid(vtkMultiProcessController* controller, cao::BitGrid& grid);
  /// `words` becomes the XOR of every process's (the same length on each).
  static bool Xor(vtkMultiProcessController* controller, std::vector<std::uint32_t>& words);
  /// `values` becomes the minimum over the processes, value by value.
  static bool Min(vtkMultiProcessController* controller, double* values, int count);
  /// `all`: every process's `mine`, one after the other (any lengths).
  static bool Gather(vtkMultiProcessController* controller, const std::vector<double>& mine,
    std::vector<double>& all);
  /// Exchanges that found a change (the grids rebuilt).
  int Changes() const { return this->ChangeCount; }

private:
  std::vector<double> Key;
  std::array<double, 6> Local{ { 1, -1, 1, -1, 1, -1 } };
  std::array<double, 6> Common{ { 1, -1, 1, -1, 1, -1 } };
  int ChangeCount = 0;
};
}
#endif
