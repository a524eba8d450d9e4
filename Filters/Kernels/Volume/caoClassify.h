/**
 * caoClassify — per-pose voxel classification with anti-aliased clipping
 * (CAO paper, section 4), no VTK.
 *
 * For every voxel the clip coverage c in [0,1] is estimated from the inside
 * test at its centre and 8 corners (x, y, z +- 0.5 voxel); where those 9
 * disagree, N extra samples (ClipParams::aaOffsets) refine it to
 * c = inside / (9 + N). The clipped opacity is a * (1 - c) in subtraction
 * mode and a * c in probing mode. Categories:
 *  - a (clipped): c == 1 (subtraction) or c == 0 (probing); opacity 0;
 *  - b (affected): not a, and the voxel centre is inside the dilated maps
 *    (subtraction) or outside the eroded maps (probing): some voxel its LAO
 *    reads may have a changed opacity;
 *  - c (unaffected): otherwise; its LAO reads only unchanged opacities.
 * Voxels outside the candidate box are c (subtraction) or a (probing).
 *
 * Inside test of a point (x, y, z) in continuous voxel index: project with
 * ClipParams::toCamera in float, in the documented order; the point is
 * inside when it falls in pixel (floor u, floor v) of the map and
 * front_l <= depth <= back_l for some layer l. The GLSL mirror does the
 * same float operations, so masks agree bit for bit.
 */
#ifndef caoClassify_h
#define caoClassify_h

#include "caoClipDepthMaps.h"
#include "caoGPULayout.h"

#include <cstdint>
#include <vector>

namespace cao
{
struct ClipMapsView
{
  const float* front = nullptr;     ///< raw layers
  const float* back = nullptr;
  const float* candFront = nullptr; ///< dilated (subtraction) or eroded (probing) layers
  const float* candBack = nullptr;
};

struct CategoryCounts
{
  std::int64_t clipped = 0, affected = 0, unaffected = 0;
  /// Of those, the voxels of the candidate box decided brick by brick
  /// (ClipMapsTiles) rather than sample by sample.
  std::int64_t byBrick = 0;
  /// Of those, the voxels of bricks (BrickMemory) that hold the category
  /// they held at the previous pose: nothing was written.
  std::int64_t unchanged = 0;
  /// Of the voxels tested one by one, those decided from their centre alone
  /// (the proof maps of ClassifyRegion) rather than from every sample.
  std::int64_t byCentre = 0;
  /// Of the voxels tested sample by sample, the transparent ones whose 9
  /// samples disagree: their anti-aliasing samples are not tested (they
  /// could change no bit).
  std::int64_t transparentShortcut = 0;
  void Add(const CategoryCounts& o)
  {
    byCentre += o.byCentre;
    transparentShortcut += o.transparentShortcut;
    clipped += o.clipped;
    affected += o.affected;
    unaffected += o.unaffected;
    byBrick += o.byBrick;
    unchanged += o.unchanged;
  }
};

/**
 * Conservative summaries of the two map sets (clip and candidate layers)
 * over square pixel tiles of 4, 16, 64, ... pixels: per tile, the smallest
 * front and the largest back over all its pixels and layers (a depth range
 * outside them meets no interval), and per layer the largest front and the
 * smallest back (a range inside them lies in that layer at every pixel).
 * An empty or NaN interval counts as empty, as the point test reads it.
 *
 * ClassifyRegion uses them to decide a whole brick of 4^3 voxels at once
 * when every sample of every voxel in it (centre, corners, anti-aliasing
 * samples: all within half a voxel of the centres) provably gives the same
 * answer as the per-sample test would; a brick it cannot prove uniform goes
 * sample by sample. It queries blocks of 4 x 4 bricks of a brick layer
 * first, and a brick only where its block is not proven uniform (where the
 * block's clip is proven uniform, the brick's candidate query alone). The result is therefore bit for bit the same with and
 * without the tiles; only the work differs.
 */
class ClipMapsTiles
{
public:
  enum Coverage : std::uint8_t
  {
    None = 0,  ///< no sample lies in any layer
    All = 1,   ///< every sample lies in a layer
    Mixed = 2  ///< cannot tell: test each sample
  };
  /// Summarise `maps` (width x height pixels, `layers` layers).
  void Build(const ClipMapsView& maps, int width, int height, int layers);
  /// Whether Build ran (for these dimensions).
  bool Built(int width, int height, int layers) const
  {
    return this->Width == width && this->Height == height && this->Layers == layers &&
      !this->Levels.empty();
  }
  /// Coverage of the samples whose camera coordinates lie in pixels
  /// [px0, px1] x [py0, py1] (clamped to the map) at depths [d0, d1], for
  /// map set `set` (0: clip layers, 1: candidate layers). `allInMap`: every
  /// sample lies inside the map (otherwise All is impossible).
  Coverage Query(int set, int px0, int px1, int py0, int py1, double d0, double d1,
    bool allInMap) const;

private:
  struct Level
  {
    int tile = 0, tilesX = 0, tilesY = 0;
    // [set][tile]: over all layers; [set][tile * layers + l]: per layer.
    std::vector<float> minFront[2], maxBack[2], maxFrontLayer[2], minBackLayer[2];
  };
  int Width = 0, Height = 0, Layers = 0;
  std::vector<Level> Levels;
};

/// A brick of 4^3 voxels as the classification decided it: every voxel in
/// one category (its clipped opacity 0, or its opacity), or Mixed (voxel by
/// voxel).
enum BrickCategory : std::uint8_t
{
  BrickMixed = 0,
  BrickClipped = 1,
  BrickAffected = 2,
  BrickUnaffected = 3
};
constexpr int BrickSize = 4;

/**
 * What the classification keeps between poses, per brick of 4^3 voxels
 * aligned to the volume (brick (I, J, K) holds voxels 4I..4I+3, ...):
 * the category every voxel of the brick holds in the buffers (or Mixed),
 * whether some voxel's opacity is not 0 (bit pattern), and, for Mixed
 * bricks, whether some voxel's clipped opacity differs from its opacity
 * (bit pattern). A brick whose category is the mode's default (Default())
 * holds the unclipped state: subtraction c and the opacity, probing a and 0.
 * A brick decided uniform at a pose with the category it already holds is
 * not written again.
 */
struct BrickMemory
{
  int bricks[3] = { 0, 0, 0 };
  std::vector<std::uint8_t> category; ///< BrickCategory per brick, x fastest
  std::vector<std::uint8_t> opaque;
  std::vector<std::uint8_t> differs;
  static std::uint8_t Default(int mode)
  {
    return mode == layout::CAO_MODE_SUBTRACT ? BrickUnaffected : BrickClipped;
  }
  /// Size for a volume of `dims`, every brick `category`; `opaque` from
  /// the opacity, bricks [zBegin, zEnd) of z (call over every layer).
  void Allocate(const int dims[3], std::uint8_t category);
  void FindOpaque(const int dims[3], const float* opacity, int zBegin, int zEnd);
  std::size_t Index(int bi, int bj, int bk) const
  {
    return static_cast<std::size_t>(bi) +
      static_cast<std::size_t>(bricks[0]) * (static_cast<std::size_t>(bj) +
        static_cast<std::size_t>(bricks[1]) * static_cast<std::size_t>(bk));
  }
  /// Whether brick m's voxels may hold a clipped opacity that differs from
  /// their opacity (bit pattern).
  bool MayDiffer(std::size_t m) const
  {
    return category[m] == BrickClipped ? opaque[m] != 0
                                       : (category[m] == BrickMixed && differs[m] != 0);
  }
};

/// Give voxels [begin, end) the unclipped state of `mode`: subtraction c
/// and the opacity, probing a and 0.
void FillUnclipped(int mode, const float* opacity, float* clippedOpacity,
  std::uint8_t* category, std::int64_t begin, std::int64_t end);

/// The factor a voxel's opacity is multiplied by when `count` of its
/// `total` = 9 + N inside samples fall in the clip (counts above total are
/// clamped): 1 - c in subtraction, c in probing, with c = count / total in
/// float, exactly the arithmetic ClassifySlices uses. The GPU keeps `count`
/// per voxel and this factor in a table.
inline float ClipFactor(int count, int total, int mode)
{
  const float coverage =
    static_cast<float>(count < total ? count : total) / static_cast<float>(total);
  return mode == layout::CAO_MODE_SUBTRACT ? 1.0f - coverage : coverage;
}

/// Fill the deterministic extra anti-aliasing sample offsets (an R3
/// low-discrepancy sequence in the voxel) and the count.
void SetAntiAliasingSamples(layout::ClipParams& params, int extraSamples);

/// Candidate box: the voxels whose centre can map into the camera-space box
/// [u0,u1] x [v0,v1] x [z0,z1] under the index-to-camera affine (double,
/// rows of a 3x4), padded by one voxel and clamped to the volume. Returns
/// false when the box is empty or the affine is singular.
bool CandidateBox(const double indexToCamera[12], const double cameraBox[6], const int dims[3],
  int boxMin[3], int boxMax[3]);

/// Narrow a candidate box to the maps' contents: the voxels whose samples
/// (within half a voxel of the centre) can map into a non-empty interval of
/// either map set, i.e. into the prism [px, px+1] x [py, py+1] x [front,
/// back] of a pixel that holds one. A shape turned against the volume's axes
/// fills far less than the box of its camera-space bounds (a sphere turned
/// by 45 degrees: about a third of it). The prisms' index-space bounds are
/// taken in double, grown by the float evaluation error of the point test
/// and by one voxel, and intersected with [boxMin, boxMax]. Returns false
/// (the box is then empty) when no pixel holds an interval in the box.
bool NarrowCandidateBox(const double indexToCamera[12], const ClipMapsView& maps, int width,
  int height, int layers, int boxMin[3], int boxMax[3]);

/// Inside test of a continuous index point against a set of layer maps.
bool InsideClip(const layout::ClipParams& p, const float* front, const float* back, float x,
  float y, float z);

/// Classify slices [zBegin, zEnd) of a volume of `dims` voxels: writes the
/// category mask and the clipped opacity for every voxel of those slices,
/// appends the affected (b) voxels in increasing linear order, and adds to
/// `counts`.
void ClassifySlices(const layout::ClipParams& p, const int dims[3], const ClipMapsView& maps,
  const float* opacity, float* clippedOpacity, std::uint8_t* category, int zBegin, int zEnd,
  std::vector<std::int64_t>& affected, CategoryCounts& counts);
/**
 * The proof maps of ClassifyRegion: layers dilated and eroded
 * (DilateErodeRows) so that one point's test decides many samples. A point
 * outside the layers dilated by r has no point within r inside them; a point
 * inside a layer eroded by r has every point within r inside it.
 * The clip layers are dilated and eroded by the reach of a voxel's samples
 * (centre, corners, anti-aliasing samples: its cube, at most SampleReach
 * from the centre), grown by twice RoundingReach (the float point test
 * moves the deciding point and the samples), so the centre decides the
 * coverage away from the surface. Built once per maps and radius. (Bricks
 * are proven by the tiles: maps dilated by a brick's reach cost 70-140 ms
 * a build on embryo's 303 x 303 x 2 maps and decided no brick the tiles
 * did not, on four shapes in both modes.)
 */
struct ProofMaps
{
  /// The largest per-voxel radius, in pixels, the maps are built for
  /// (beyond, Prepare builds none): the dilation's window grows with the
  /// square of the radius in pixels.
  static constexpr double MaxProofPixels = 8.0;
  /// The largest distance (local units) from a voxel's centre to a point
  /// of its cube under `clip`'s index-to-camera map, for pixels of
  /// `pixelSize` local units.
  static double SampleReach(const layout::ClipParams& clip, const double pixelSize[2]);
  /// A bound on how far (local units) the float point test moves a point of
  /// a volume of `dims` voxels from where it lies.
  static double RoundingReach(
    const layout::ClipParams& clip, const double pixelSize[2], const int dims[3]);

  /// What ClassifyRegion reads.
  struct View
  {
    /// The clip layers dilated (front/back) and eroded (candFront/candBack).
    ClipMapsView sample;
    /// Per pixel and layer (pixel * layers + l), 8 floats: the clip
    /// layers' front and back, the candidate layers', `sample`'s dilated
    /// and eroded ones, so that a voxel's centre tests read one record (one
    /// cache line for up to two layers; a profile put 38% of the
    /// classification on the layer test's loads when the maps were read
    /// apart, and the record took 8% off its time on embryo's sphere path).
    /// Copies of the maps Prepare was given: valid while they are the
    /// maps ClassifyRegion reads (ContextualUpdate prepares them in the
    /// same pose). Null: `sample` and the maps are read.
    const float* packed = nullptr;
  };

  /// The maps for `clip` (pixel sizes as the maps were made with; null: none,
  /// false): rebuilt only when `version` or the layers change or the radius
  /// needed leaves [0.67, 1] of the built one.
  bool Prepare(const layout::ClipParams& clip, const ClipMapsView& maps, std::uint64_t version,
    const double pixelSize[2], const int dims[3], View& view);

  ClipDepthMaps clip, cand;                                  ///< copies of the layers
  ClipDepthMaps sample[2];                                   ///< dilated, eroded
  std::vector<float> packedStore; ///< View::packed, at packedOffset (aligned)
  std::size_t packedOffset = 0;
  double radius = -1.0; ///< the per-voxel radius they were built for (local units)
  std::uint64_t version = 0;
  const float* of[4] = { nullptr, nullptr, nullptr, nullptr };
  int builds = 0; ///< how many times they were built (tests)
};

/// ClassifySlices within `region` (x0, x1, y0, y1, z0, z1, inclusive, which
/// must contain the candidate box) only: voxels outside it are not written
/// and not counted. The contextual update classifies the union of this
/// pose's box and the previous pose's, outside which nothing can change.
/// Slice k's affected voxels go to affectedBySlice[k - zBegin] (cleared
/// first; the caller keeps these lists between poses, so their memory is
/// reused). With `tiles` (built from `maps`), bricks proven uniform are
/// decided at once; the result is the same bit for bit.
/// With `memory` (whose buffers describe `clippedOpacity` and `category`),
/// the candidate box must start on a brick (a multiple of BrickSize on
/// each axis), `region` must equal it, and each call must cover whole
/// layers of bricks: a brick decided uniform with the category it holds
/// is not written, and `memory` is updated for every brick of the slices.
/// With `proof` (ProofMaps), a voxel whose centre lies outside the clip
/// dilated by its samples' reach, or inside it eroded, has every sample out
/// of the clip or in it and is decided from its centre alone (the tests
/// read the proof's packed record when it has one); the result is the same
/// bit for bit.
void ClassifyRegion(const layout::ClipParams& p, const int dims[3], const ClipMapsView& maps,
  const float* opacity, float* clippedOpacity, std::uint8_t* category, const int region[6],
  int zBegin, int zEnd, std::vector<std::int64_t>* affectedBySlice, CategoryCounts& counts,
  const ClipMapsTiles* tiles = nullptr, BrickMemory* memory = nullptr,
  const ProofMaps::View* proof = nullptr);

}

#endif
