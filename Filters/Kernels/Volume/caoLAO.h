/**
 * caoLAO — the local ambient occlusion ray march (Hernell et al.), no VTK.
 *
 * For voxel v, ray k and sample m = 1..M at distance m*s (s = R/M):
 *   A_k = (1/M) * sum_{m=1..M} prod_{i<m} (1 - a_i),
 * with a_i the opacity trilinearly interpolated at sample i (samples outside
 * the volume are transparent). The voxel's value is the mean of A_k over the
 * K rays, computed as (sum_k sum_m T_{k,m}) / (K*M) in float.
 *
 * Because every voxel uses the same ray offsets, the plan precomputes, per
 * (ray, sample), the integer cell offset and the trilinear fractions
 * (caoGPULayout.h's LAOTap). The march is then a fixed stencil; the CPU code
 * here and the GLSL compute shader run the same arithmetic in the same order
 * (nested lerps x + t*(y - x), x first), so one plan drives both backends.
 *
 * Bit-exactness contract: LAOVoxel's result depends only on the plan and on
 * the opacity values it reads. Voxels whose taps are all in bounds take a
 * fast path without bounds checks; the others substitute 0 for out-of-bounds
 * corners in the same operation order, so both paths give identical bits.
 * Compile with -ffp-contract=off (CMake does) so no FMA changes rounding.
 */
#ifndef caoLAO_h
#define caoLAO_h

#include "caoLAOSettings.h"
#include "caoRayPattern.h"
#include "caoGPULayout.h"
#include "caoMemory.h" // MaxVoxels
#include "caoOpacity.h" // CorrectOpacity

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace cao
{
/// Grid geometry of a volume: voxel counts, spacing and the 3x3 direction
/// matrix (row-major, index axes as columns) of the image.
struct VolumeGeometry
{
  int dims[3] = { 0, 0, 0 };
  /// Global index of voxel (0, 0, 0): the extent's minimum. Interleaved ray
  /// variations pick a voxel's variant from the parity of its global index,
  /// so a piece of a volume gets the values the whole volume gets.
  int origin[3] = { 0, 0, 0 };
  double spacing[3] = { 1, 1, 1 };
  double direction[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  std::int64_t NumberOfVoxels() const
  {
    return static_cast<std::int64_t>(dims[0]) * dims[1] * dims[2];
  }
  bool operator==(const VolumeGeometry& o) const
  {
    return std::equal(dims, dims + 3, o.dims) && std::equal(origin, origin + 3, o.origin) &&
      std::equal(spacing, spacing + 3, o.spacing) && std::equal(direction, direction + 9, o.direction);
  }
  bool operator!=(const VolumeGeometry& o) const { return !(*this == o); }
};

/// Everything the march needs; uploadable as-is to a GPU (params + taps).
struct LAOPlan
{
  layout::LAOMarchBlock params{};
  std::vector<layout::LAOTap> taps; ///< V * K * (M-1) taps: variant-major, then ray-major
  std::vector<Direction> directions; ///< variant 0's K directions
  int variants = 1;                  ///< V: 1, or 8 for an interleaved variation
  double reach = 0.0;
  double step = 0.0; ///< world distance between samples, R / M
  int rays = 0;
  int samples = 0;
};

/// Default number of samples for a reach: `density` per smallest voxel
/// spacing, max(2, round(density * R / h_min)); above LAOLimits::MaxSamples
/// it returns MaxSamples + 1 (BuildLAOPlan then refuses the plan).
int DefaultSampleCount(double reach, const double spacing[3], double density = 1.0);

/// The fixed rotation (row-major 3x3) of interleaved variant v in [0, 8).
void VariationRotation(int v, double rotation[9]);

/// Build a plan for the settings resolved (ResolveLAOSettings: the preset
/// applied, the reach's default); false with a message for invalid ones.
bool BuildLAOPlan(
  const VolumeGeometry& geometry, const LAOSettings& settings, LAOPlan& plan, std::string& error);

/// LAO of one voxel (i, j, k) over an opacity volume laid out x-fastest.
float LAOVoxel(const LAOPlan& plan, const float* opacity, int i, int j, int k);

/// LAO of the voxels with linear index in [begin, end).
void LAORange(
  const LAOPlan& plan, const float* opacity, float* ao, std::int64_t begin, std::int64_t end);
/// The same, stored as 16-bit unsigned normalised AO (QuantizeAO of what
/// the float LAORange writes: the GPU precompute's storage).
void LAORange(const LAOPlan& plan, const float* opacity, std::uint16_t* ao, std::int64_t begin,
  std::int64_t end);

/// LAO of one voxel like LAOVoxel, from the same plan and opacities, but
/// with every operation in double: the reference for the float
/// accumulation error (same sample positions, same order).
double LAOVoxelDouble(const LAOPlan& plan, const float* opacity, int i, int j, int k);

/// The instruction set the run march (LAORange, LAOList) uses on this
/// processor: "avx2" or "baseline" (the build's target; also when
/// CAO_LAO_BASELINE=1). Both give the same bits.
const char* LAOMarchInstructionSet();

/// LAO of the listed voxels (linear indices list[begin..end)), written in place.
void LAOList(const LAOPlan& plan, const float* opacity, float* ao, const std::int64_t* list,
  std::int64_t begin, std::int64_t end);

/// The same, stored as 16-bit unsigned normalised AO (QuantizeAO of the
/// float LAOList would write: the same march, the same bits before storage).
void LAOList(const LAOPlan& plan, const float* opacity, std::uint16_t* ao,
  const std::int64_t* list, std::int64_t begin, std::int64_t end);

/// AO in [0, 1] as 16-bit unsigned normalised: q = ao * 65535 + 0.5 in float,
/// truncated (the GPU's storage, mirrored by caoLAOMarch.glsl's Quantize;
/// the one C++ definition, for every reader and writer; a caller compiles
/// it with -ffp-contract=off, as the kernels and the VTK modules that use
/// it are, so that no FMA contracts it).
inline std::uint16_t QuantizeAO(float ao)
{
  return static_cast<std::uint16_t>(ao * static_cast<float>(layout::CAO_AO_SCALE) + 0.5f);
}
/// The stored value back to float (q / 65535).
inline float DequantizeAO(std::uint16_t q)
{
  return static_cast<float>(q) / static_cast<float>(layout::CAO_AO_SCALE);
}

/// The AO the plan gives a point on the open flat face of an opaque
/// half-space, `depth` voxels past the last empty voxel layer (0: that
/// layer, 1: the first opaque one, between: trilinear): the mean over the
/// six axis-aligned faces and every ray variant, in closed form from the
/// plan's taps (the opacity of an axis-aligned half-space depends on one
/// coordinate), in double, with the march's order of operations.
double HalfSpaceAO(const LAOPlan& plan, double depth);

/// The same for a half-space of matter whose full voxel layers have the
/// LAO-step opacity `opacity` (the layer before the face empty, the
/// trilinear ramp between), at any depth >= 0 (linear between layers;
/// deep inside it tends to the enclosed value of that matter).
double HalfSpaceAO(const LAOPlan& plan, double depth, double opacity);

/// HalfSpaceAO at the integer depths 0 .. CAO_HALF_SPACE_LAYERS - 1 and the
/// opacities o / (CAO_HALF_SPACE_OPACITIES - 1), as the ray caster reads it
/// (RenderParams::halfSpace, element depth * CAO_HALF_SPACE_OPACITIES + o).
std::vector<float> HalfSpaceTable(const LAOPlan& plan);

/// The range the plan's LAO spans at the surface of opaque matter
/// (reported by vtkContextualAOVolumeMapper::GetAOCalibrationRange; the
/// ray caster's calibration reads HalfSpaceTable, which holds these at
/// opacity 1).
///
/// A point on a surface receives ambient light from its outer hemisphere
/// only. LAO averages over the whole sphere, and its first sample is never
/// occluded, so the LAO of a surface voxel runs from `enclosed` (1/M: every
/// ray blocked at once, a closed cavity) to the value of an open flat face
/// (`openEmpty` for the last empty voxel, `openOpaque` for the first opaque
/// one, HalfSpaceAO at depth 0 and 1).
struct AOCalibration
{
  double openEmpty = 1.0, openOpaque = 1.0, enclosed = 0.0;
};
AOCalibration SurfaceCalibration(const LAOPlan& plan);
}

#endif
