/**
 * vtkCAOSceneExchange — what the processes that render one scene together
 * (parallel rendering: each draws its own pieces, the images composited by
 * depth) agree on for the surface AO: whether any process's scene changed
 * this frame, the bounds of every process's pieces together, and the grid
 * combined from every process's voxels (per actor its pieces' parities
 * XOR-ed, then the processes' grids OR-ed). Every call here is collective:
 * every process calls Frame at every frame, and CommonBounds and
 * CombineGrid in the same order whenever Frame says a scene changed,
 * whatever it holds (no pieces, a failed voxelization: zeros).
 */
#ifndef vtkCAOSceneExchange_h
#define vtkCAOSceneExchange_h

#include "caoRenderingSceneModule.h" // For export macro

#include "caoSceneGrid.h" // For cao::BitGrid

#include <array>      // For the bounds
#include <cstdint>    // For the words
#include <functional> // For the local bounds
#include <string>     // For the reason
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
  /// The world or eye grid `grid` (planned alike on every process) of the
  /// pieces here, `pieceActor` naming each piece's actor among `actors`
  /// (`signature`: which of the renderer's actors they are), combined with
  /// every process's: per actor its pieces' parities XOR-ed across the
  /// processes (a closed mesh split between them is filled as on one
  /// process), or its own where the same whole actor is on every process
  /// (replicated: XOR-ing identical parities would cancel its inside);
  /// closed when its pieces' open edges match up over the processes (ends
  /// within `tolerance` are one point) and every column is crossed an even
  /// number of times, its inside and surface voxels, else its pieces'
  /// shells; the processes' grids then OR-ed. If the actors differ between
  /// processes, shells only. grid.openEdges: per actor 0 (closed) or 1.
  /// False, with the reason, when this process's pieces failed (its share
  /// then zeros) or the exchange failed.
  static bool CombineGrid(vtkMultiProcessController* controller, const std::vector<cao::MeshView>& pieces,
    const std::vector<int>& pieceActor, int actors, double signature, double tolerance, cao::BitGrid& grid,
    std::string& error);
  /// The area of every process's pieces together (`pieces` as CombineGrid
  /// takes them): per actor the processes' areas summed, or one process's
  /// where the same whole actor is on every process (replicated, found as
  /// CombineGrid finds it); if the actors differ between processes, every
  /// piece's area summed. False when the exchange failed (`area` is then
  /// this process's).
  static bool CommonArea(vtkMultiProcessController* controller, const std::vector<cao::MeshView>& pieces,
    const std::vector<int>& pieceActor, int actors, double signature, double& area);
  /// The bounds of every process's `local` bounds together (min > max: none).
  static bool CommonBounds(vtkMultiProcessController* controller, std::array<double, 6>& bounds);
  /// Exchanges that found a change (the grids rebuilt).
  int Changes() const { return this->ChangeCount; }

  /// `values` becomes the minimum over the processes, value by value.
  static bool Min(vtkMultiProcessController* controller, double* values, int count);
  /// `all`: every process's `mine`, one after the other (any lengths).
  static bool Gather(vtkMultiProcessController* controller, const std::vector<double>& mine,
    std::vector<double>& all);

private:
  /// `words` becomes the XOR of every process's (the same length on each).
  static bool Xor(vtkMultiProcessController* controller, std::vector<std::uint32_t>& words);
  std::vector<double> Key;
  std::array<double, 6> Local{ { 1, -1, 1, -1, 1, -1 } };
  std::array<double, 6> Common{ { 1, -1, 1, -1, 1, -1 } };
  int ChangeCount = 0;
};
}
#endif
