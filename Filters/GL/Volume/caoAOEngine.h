/**
 * caoAOEngine — contextual ambient occlusion on the GPU, with no VTK: the
 * LAO precompute, the per-pose classification, the copy of category a/c
 * values and the category-b recompute, as compute passes over GPU-resident
 * volumes. The arithmetic mirrors the CPU kernels (caoLAO, caoClassify) on
 * the same caoGPULayout.h blocks, so the two backends agree.
 *
 * Resident storage, per voxel (the paper keeps five float volumes):
 *  - the input: 8- or 16-bit scalars with an opacity table (exact: the CPU
 *    evaluates the transfer function per scalar value too), or float opacity;
 *  - the clip state: one byte, category << 6 | anti-aliasing coverage count;
 *    the clipped opacity is recomputed on the fly as opacity * factor[count];
 *  - the precomputed and the current AO: 16-bit unsigned normalised each.
 * For an 8-bit input that is 1 + 1 + 2 + 2 = 6 bytes per voxel.
 *
 * Only the region that can change is touched per pose: the union of this
 * pose's candidate box and the previous one. Outside it every voxel already
 * holds the outside state (c in subtraction, a in probing) and the
 * precomputed AO.
 *
 * Every call needs the engine's context current (MakeCurrent is called for
 * headless contexts). Each stage is timed with GL_TIME_ELAPSED queries.
 */
#ifndef caoAOEngine_h
#define caoAOEngine_h

#include "caoClipDepthMapsGL.h"
#include "caoGLContext.h"
#include "caoLAO.h"
#include "caoGPULayout.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace cao
{
namespace gl
{
enum class OpacitySource
{
  Float32 = 0,   ///< float opacity per voxel
  Scalars8 = 1,  ///< uint8 scalars + a 256-entry opacity table
  Scalars16 = 2, ///< uint16 scalars + a 65536-entry opacity table
};

struct VolumeUpload
{
  int dims[3] = { 0, 0, 0 };
  OpacitySource source = OpacitySource::Float32;
  const void* data = nullptr;      ///< x-fastest, matching `source`
  std::vector<float> opacityTable; ///< Scalars8/16: corrected opacity per value
};

/// GPU milliseconds of the last run of each stage (timer queries); -1 = not run.
struct StageTimes
{
  double precompute = -1, depthMaps = -1, dilate = -1, classify = -1, copy = -1,
         recompute = -1, full = -1;
};

struct UpdateStats
{
  std::int64_t clipped = 0, affected = 0, unaffected = 0; ///< whole volume
  std::int64_t regionVoxels = 0;                          ///< voxels classified this pose
};

class AOEngine
{
public:
  /// The engine borrows the context; it must outlive the engine.
  explicit AOEngine(Context& context);
  ~AOEngine();
  AOEngine(const AOEngine&) = delete;
  AOEngine& operator=(const AOEngine&) = delete;

  /// Upload the volume (replaces any previous one; the AO must be recomputed).
  bool SetVolume(const VolumeUpload& volume, std::string& error);
  /// Upload the LAO plan (taps, parameters) and build the programs.
  bool SetPlan(const LAOPlan& plan, std::string& error);
  /// Full, unclipped LAO into the precomputed AO; current AO = precomputed,
  /// every voxel unclipped. `progress(fraction)` may return false to abort.
  bool Precompute(std::string& error, const std::function<bool(double)>& progress = nullptr);
  /// Upload a precomputed AO instead (stored values, q = ao * 65535 + 0.5),
  /// e.g. what this engine's Precompute produced in another filter on the
  /// same driver; the CAO exactness holds only for such values.
  bool SetPrecomputed(const std::uint16_t* ao, std::string& error);
  bool HasPrecomputed() const;

  /// Upload clip depth maps (raw and candidate layers, caoClipDepthMaps layout).
  bool SetMaps(int width, int height, int layers, const float* front, const float* back,
    const float* candidateFront, const float* candidateBack, std::string& error);

  /// Take the maps a ClipDepthMapsGL built on this engine's context, without a
  /// CPU round trip: raw layers plus the dilated (subtraction) or eroded
  /// (probing) pair, chosen by `mode` (CAO_MODE_*). A pose of the other mode
  /// needs this call again.
  bool SetMaps(const ClipDepthMapsGL& raster, int mode, std::string& error);

  /// How a pose's AO is produced.
  enum class UpdateMode
  {
    Contextual, ///< the paper's: classify the candidate region, recompute category b
    Full,       ///< classify every voxel, recompute every voxel not in category a
  };
  /// One pose: classify, copy categories a/c, recompute category b. With
  /// UpdateMode::Full, the reference the contextual update must equal: the
  /// same state and the same category-a values (the precomputed AO), and
  /// the clipped LAO of every other voxel, recomputed.
  bool Update(const layout::ClipParams& clip, UpdateStats& stats, std::string& error,
    UpdateMode mode = UpdateMode::Contextual);
  /// A pose's state and AO made on the CPU (ContextualUpdate: the same
  /// categories and, on the same march, the same stored AO): `clip` as
  /// SetClipParams takes it, and of the whole-volume arrays `category`
  /// (CAO_CATEGORY_*) and `ao` (16-bit), the box `region` (x0, x1, y0, y1,
  /// z0, z1, inclusive), which must hold every voxel that changed since
  /// the state and AO the engine holds. The state keeps the category only
  /// (a renderer reads no more of it); an Update after this starts from the
  /// whole volume again.
  bool SetClipState(const layout::ClipParams& clip, const std::uint8_t* category,
    const std::uint16_t* ao, const int region[6], std::string& error);
  /// Upload a pose's ClipParams for a renderer's shadow test only: no
  /// classification, no AO (for rendering with the AO off). Needs SetVolume.
  bool SetClipParams(const layout::ClipParams& clip, std::string& error);
  /// Back to the unclipped state: current AO = precomputed everywhere.
  bool ResetClip(std::string& error);

  /// The full recompute on the current clip state, for verification: the
  /// clipped LAO of every voxel not in category a (others are left 0).
  bool FullRecompute(std::vector<std::uint16_t>& ao, std::string& error);

  struct Verification
  {
    std::int64_t storedMismatches = 0; ///< voxels whose stored AO != the full recompute's
    std::int64_t floatMismatches = 0;  ///< category-c voxels whose clipped LAO != unclipped, in float
    double maxFloatDifference = 0.0;
  };
  /// Verify the current AO without any extra volume: every voxel not in
  /// category a is recomputed on the clipped opacity and compared with the
  /// stored value; every category-c voxel is also marched on the unclipped
  /// opacity and compared in float, bit for bit, which checks the
  /// classification itself below the 16-bit storage step.
  bool Verify(Verification& result, std::string& error);

  bool ReadCurrentAO(std::vector<std::uint16_t>& ao, std::string& error);
  bool ReadPrecomputedAO(std::vector<std::uint16_t>& ao, std::string& error);
  bool ReadState(std::vector<std::uint8_t>& state, std::string& error);

  const StageTimes& Times() const;

  /// What a renderer on the same context samples (GL names; 0 when absent).
  /// `generation` changes whenever the volumes are re-created, so that a
  /// renderer's texture views of them can tell they are stale.
  struct Resources
  {
    unsigned int volume = 0, state = 0, currentAO = 0, precomputedAO = 0, maps = 0, clipParams = 0;
    unsigned int opacityTable = 0; ///< storage: the LAO's opacity per scalar value (Scalars8/16)
    OpacitySource source = OpacitySource::Float32;
    int dims[3] = { 0, 0, 0 };
    std::uint64_t generation = 0;
    /// `contents` counts the writes to the state and the AO; the last one
    /// took it from `changedFrom` and wrote the voxels in
    /// [changedMin, changedMax] (inclusive; empty when min > max). A
    /// renderer that derived something from them at `changedFrom` needs to
    /// redo only that box.
    std::uint64_t contents = 0, changedFrom = 0;
    int changedMin[3] = { 0, 0, 0 }, changedMax[3] = { -1, -1, -1 };
    /// Counts every call that may have changed what a renderer reads (the
    /// volumes, maps, clip parameters, state or AO): a renderer that kept
    /// a draw of the same count needs no new one for the engine's sake.
    std::uint64_t edits = 0;
  };
  Resources GetResources() const;
  /// Bytes resident on the GPU now: volumes, tables, maps, parameters.
  std::int64_t ResidentBytes() const;
  /// Bytes of the per-voxel volumes only (input, state, two AO volumes).
  std::int64_t VolumeBytes() const;
  /// GL objects (buffers, textures, programs, queries) this engine owns.
  int LiveObjects() const;
  /// Names of those objects, as (kind, name) with kind 'b', 't', 'p' or 'q'.
  std::vector<std::pair<char, unsigned int>> ObjectNames() const;
  /// Delete every GL object; the engine can be set up again afterwards.
  void ReleaseGraphicsResources();
  /// Forget every GL object without a GL call, for when the context that
  /// held them is gone (a destroyed render window); the destructor then
  /// touches no GL either.
  void AbandonGraphicsResources();

  Context& GetContext();

  /// AO as stored on the GPU (q / 65535) back to float.
  static float Dequantize(std::uint16_t q) { return DequantizeAO(q); }
  /// AO in [0, 1] as the GPU stores it, q = ao * 65535 + 0.5 in float (the
  /// shaders' Quantize).
  static std::uint16_t Quantize(float ao) { return QuantizeAO(ao); }

private:
  struct Impl;
  std::unique_ptr<Impl> P;
};
}
}

#endif
