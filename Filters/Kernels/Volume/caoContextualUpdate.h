/**
 * caoContextualUpdate — the contextual AO update on the CPU: the twin of
 * gl::AOEngine::Update (CAO paper, section 4). No VTK.
 *
 * Per pose: classify the voxels (clipped a, affected b, unaffected c) with
 * the anti-aliased clip test, give every voxel not in b the precomputed AO,
 * and recompute the b voxels on the clipped opacity with the LAO plan's
 * march. The result equals a full recompute of the clipped volume bit for
 * bit (Verify checks it).
 *
 * Narrowed by opacity: a b voxel whose footprint (caoOpacityEdit) holds no
 * voxel whose clipped opacity differs from its opacity (the clip removed
 * only transparent matter near it) reads the same opacities as the
 * precompute did, so it keeps its precomputed AO bit for bit and is not
 * marched. The test runs per brick of 4^3 voxels (BrickMemory::MayDiffer,
 * dilated by the footprint in bricks): conservative, so a voxel is marched
 * whenever its brick's footprint may hold such a voxel. The categories stay
 * the paper's (geometric); Stats says how many b voxels were marched. Like
 * the c voxels, an unmarched b voxel keeps the given precomputed AO: it
 * equals a full recompute when that AO is the LAO of `opacity` with `plan`
 * (Verify's contract for c voxels too).
 *
 * The buffers (AO, clipped opacity, category) are the caller's and persist
 * between poses, with a BrickMemory that says which category every brick
 * holds: a pose touches only what can have changed since the previous one.
 * The previous pose's marched voxels get their precomputed AO back; the
 * bricks of the previous pose's box (grown to whole bricks) outside this
 * pose's box that hold a clipped state get the unclipped one; this pose's
 * box is classified, and a brick proven uniform with the category it
 * already holds is not written. The first pose, and any after Reset() or a
 * change of mode, writes every voxel.
 *
 * Parallel work goes through a ParallelFor the caller provides (the VTK
 * layer passes vtkSMPTools with progress and abort), so the results never
 * depend on the thread count: the b voxels are kept per slice, in order.
 */
#ifndef caoContextualUpdate_h
#define caoContextualUpdate_h

#include "caoClassify.h"
#include "caoLAO.h"

#include <cstdint>
#include <functional>
#include <vector>

namespace cao
{
class ContextualUpdate
{
public:
  /// body(begin, end) over [0, n) in parallel, progress from p0 to p1;
  /// false when aborted (the update then stops and Reset()s).
  using ParallelFor = std::function<bool(std::int64_t n, std::int64_t grain, double p0,
    double p1, const std::function<void(std::int64_t, std::int64_t)>& body)>;

  /// The volume's inputs, unchanged between poses (the caller Reset()s when
  /// any of them changes).
  struct Volume
  {
    VolumeGeometry geometry;
    const LAOPlan* plan = nullptr;
    const float* opacity = nullptr;     ///< unclipped, step-corrected
    const float* precomputed = nullptr; ///< the LAO of `opacity` with `plan`
    /// Instead of `precomputed` (Update only, with Buffers::ao16): that LAO
    /// as stored in 16 bits (QuantizeAO of it), which the restored voxels
    /// get as it is: half the memory of a float copy, the same bits.
    const std::uint16_t* precomputed16 = nullptr;
  };
  /// The outputs, kept by the caller between poses (contents included).
  /// The AO is written to exactly one of `ao` (float) and `ao16` (16-bit
  /// unsigned normalised, QuantizeAO of the float value: 2 bytes a voxel
  /// instead of 4, as the GPU stores it).
  struct Buffers
  {
    float* ao = nullptr;
    std::uint16_t* ao16 = nullptr;
    float* clippedOpacity = nullptr;
    std::uint8_t* category = nullptr;
  };
  struct Stats
  {
    CategoryCounts counts; ///< counts.byBrick: voxels decided brick by brick
    /// voxels written by the classification: every voxel at a first pose;
    /// then this pose's box less its unchanged bricks, and the bricks reset
    /// to the unclipped state
    std::int64_t classifiedVoxels = 0;
    std::int64_t restoredVoxels = 0;   ///< previous recomputed voxels given their precomputed AO back
    /// b voxels marched: those whose footprint holds a voxel whose clipped
    /// opacity differs from its opacity (the others keep their precomputed
    /// AO exactly); counts.affected is the paper's geometric b
    std::int64_t recomputedVoxels = 0;
    double narrowMs = 0; ///< the footprint test of the b voxels (per brick)
    double classifyMs = 0, copyMs = 0, recomputeMs = 0;
    /// The unclipped state written to every voxel (the precomputed AO, the
    /// opacity, the unclipped category, the bricks' memory): the first pose
    /// after Reset() or a change of mode only, before that pose's own
    /// classification; it does not depend on the pose; not in classifyMs or
    /// copyMs. Also the summaries of new maps (their tiles and proof maps,
    /// built once per maps version as the maps themselves are), whatever
    /// the pose; remade for the same maps (no version, another reach), they
    /// are in classifyMs.
    double setupMs = 0;
  };

  /// Forget the previous pose: the next Update writes every voxel.
  void Reset();

  /// One pose. `clip` and `maps` as the classifier takes them; `mapsVersion`
  /// changes whenever the maps' contents may have (0: unknown, every call).
  /// The maps' tile summaries (ClipMapsTiles) are rebuilt only then.
  /// `useTiles` false classifies sample by sample everywhere (same result).
  /// False when aborted (the buffers are then incomplete and the state reset).
  /// `pixelSize`: the maps' pixel sizes in their local units (null: unknown);
  /// with them (and `useTiles`), voxels near the clip surface are decided
  /// from their centre where the proof maps allow (ProofMaps; same result).
  bool Update(const Volume& volume, const layout::ClipParams& clip, const ClipMapsView& maps,
    std::uint64_t mapsVersion, const Buffers& buffers, const ParallelFor& parallel, Stats& stats,
    bool useTiles = true, const double* pixelSize = nullptr);


  /// The full recompute of the clipped volume (LAORange over every voxel)
  /// against the buffers' AO, over the voxels not clipped, bit for bit
  /// (with `ao16`, the full recompute's values quantized by QuantizeAO):
  /// the number that differ and the largest difference.
  static bool Verify(const Volume& volume, const Buffers& buffers, const ParallelFor& parallel,
    std::int64_t& differing, double& maxDifference, double& ms);

private:
  bool NarrowByBricks(const Volume& volume, const int box[6]);

  bool Valid = false;
  int Mode = -1;
  int Box[6] = { 0, -1, 0, -1, 0, -1 }; ///< the previous pose's candidate box grown to bricks (inclusive)
  BrickMemory Bricks;
  std::vector<std::uint8_t> Reach, ReachScratch; ///< scratch: the footprint test over bricks
  /// Per slice of the volume: the b voxels to march, in increasing order;
  /// after the pose, those marched (restored at the next pose).
  std::vector<std::vector<std::int64_t>> SliceLists;
  ClipMapsTiles Tiles;
  ProofMaps Proof;
  std::uint64_t TilesVersion = 0;
  const float* TilesOf[4] = { nullptr, nullptr, nullptr, nullptr };
};
}

#endif
