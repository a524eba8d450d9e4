/**
 * vtkCAOLineTechnique.h — the line AO techniques, as steps that
 * vtkContextualAOPass runs by its LineMethod value, on the CPU or the
 * window's OpenGL, with the lines' shared parts its own: their segments,
 * the lines' G-buffer (each drawn line pixel's segment, surface point and
 * tangent, cao::LineFrame), their eye grid (the lines' supercover, with
 * the meshes beside them voxelized as solids) and the combine. The
 * surfaces' techniques are vtkCAOSurfaceTechnique.h's, chosen apart
 * (Method): a frame runs one technique per kind of geometry.
 *
 * Each built-in is registered from Techniques/, in its own file (line
 * voxelization read by rays or prisms, value 1). A new technique is its own
 * files and one RegisterLineTechnique call (and, for ParaView, an entry in
 * the view's Line AO Method list), with no edit to the pass:
 * RenderingScene.TestLineTechnique registers one from the test's own file.
 */
#ifndef vtkCAOLineTechnique_h
#define vtkCAOLineTechnique_h

#include "caoRenderingSceneModule.h" // For export macro

#include <functional> // For the steps
#include <string>     // For the names

namespace cao
{
struct BitGrid;
struct LineAOSettings;
struct LineFrame;
}

namespace vtkCAO
{
class SceneGPU;

/// What the pass gives a line technique each frame. The pointers are the
/// pass's own: valid while the step runs, not after.
struct LineTechniqueSettings
{
  /// The AO radius (the pass's Radius, or the default of the lines'
  /// extent), the lines' tube radius (their drawn width at their centre),
  /// LineSamples and LineSlices: resolved and checked.
  const cao::LineAOSettings* lineAO = nullptr;
  /// The lines' eye grid: their supercover as tubes of the tube radius
  /// (when the AO runs on the GPU and one process holds the lines, its
  /// plan, with the bits voxelized there and none on the host; with
  /// several processes the grid of every process's lines, made on the CPU.
  /// A technique without a `gpu` step runs on the CPU, grid and all).
  const cao::BitGrid* grid = nullptr;
  /// The meshes beside the lines in that grid's plan, voxelized as solids
  /// (null: none), occluding the lines.
  const cao::BitGrid* solids = nullptr;
};

/// One line technique: the AO of the frame's line pixels (`frame`: a
/// cao::LineFrame whose covered pixels, segment >= 0, hold their point,
/// tangent and view) into frame.ao.
struct LineTechnique
{
  int method = -1;   ///< the pass's LineMethod value: 1 or more (0 is None), unique
  std::string name;  ///< the frame report's lines "method" ("lineao")
  std::string label; ///< in messages ("line AO")
  /// On the CPU (required).
  std::function<bool(const LineTechniqueSettings& settings, cao::LineFrame& frame, std::string& error)> cpu;
  /// The same on the window's OpenGL (null: the grid, the G-buffer and
  /// `cpu` run on the host).
  std::function<bool(SceneGPU& gpu, const LineTechniqueSettings& settings, cao::LineFrame& frame,
    std::string& error)>
    gpu;
  /// On the G-buffer that SceneGPU::LineGBuffer made on the GPU (it holds
  /// the segments only; null: the G-buffer is made on the CPU and `gpu`
  /// runs). Only with a `gpu` step (else refused).
  std::function<bool(SceneGPU& gpu, const LineTechniqueSettings& settings, cao::LineFrame& frame,
    std::string& error)>
    gpuOfGBuffer;
};

/// Register `technique`; false, saying why in `error`, when its method is
/// not 1 or more (0 is None) or is taken, or it has no name or no `cpu`
/// step, or a `gpuOfGBuffer` step without a `gpu` step. The built-in (line voxelization read by rays, 1) is
/// registered first.
CAORENDERINGSCENE_EXPORT bool RegisterLineTechnique(const LineTechnique& technique, std::string* error = nullptr);

/// The line technique of LineMethod value `method`, or null.
CAORENDERINGSCENE_EXPORT const LineTechnique* FindLineTechnique(int method);
/// The line technique named `name` (its report name: `cao surface --method`), or null.
CAORENDERINGSCENE_EXPORT const LineTechnique* FindLineTechniqueNamed(const std::string& name);

/// The registered line methods and names, in method order ("1 lineao").
CAORENDERINGSCENE_EXPORT std::string LineTechniqueList();
}

#endif
