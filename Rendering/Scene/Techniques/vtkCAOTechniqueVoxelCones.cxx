// Voxel cone tracing (Dalla Favera and Celes 2012) as a technique of the
// pass that reads the scene's grid (the surfaces' voxels, with the lines'
// voxels and the volumes' opacity occluding through it): cao::VCTFrame on
// the CPU, its GL twin on the window's OpenGL (read back, or kept on the
// GPU frame).
#include "vtkCAOSurfaceTechnique.h"

#include "caoFrameGL.h"
#include "caoVCTGL.h"
#include "caoVoxelConeTracing.h"
#include "vtkCAOSceneGPU.h"

#include <limits>
#include <vector>

namespace vtkCAO
{
bool RegisterBuiltIn(const SurfaceTechnique& technique);

namespace
{
/// The cones' plan on the frame's grid, with the volumes occluding.
bool PlanOf(const SurfaceTechniqueSettings& s, cao::VCTPlan& plan, std::string& error)
{
  if (!s.grid)
  {
    error = "Voxel Cones: no grid (the pass gives one to a technique that reads it)";
    return false;
  }
  cao::VCTSettings settings;
  if (const auto* own = std::any_cast<cao::VCTSettings>(&s.own))
    settings = *own; // (a caller's, whole)
  else
  {
    settings.quality = static_cast<cao::Quality>(s.quality);
    settings.slices = s.slices;
    settings.radius = s.radius;
    settings.occupancy = static_cast<cao::VCTOccupancy>(s.occupancy);
  }
  if (!cao::BuildVCTPlan(settings, *s.grid, plan, error))
    return false;
  if (s.volumes)
    for (const cao::OpacityVolume* volume : *s.volumes)
      plan.volumes.push_back(volume);
  return true;
}

/// A radius under the grid's voxel (cao::VCTUnresolvedRadius): no AO.
bool Unresolved(const SurfaceTechniqueSettings& s)
{
  const auto* own = std::any_cast<cao::VCTSettings>(&s.own);
  return s.grid && !cao::VCTUnresolvedRadius(own ? own->radius : s.radius, *s.grid).empty();
}

/// No AO (1) on the covered pixels.
void NoAO(cao::SurfaceFrame& frame)
{
  frame.ao.resize(frame.triangle.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 0; i < frame.triangle.size(); ++i)
    if (frame.triangle[i] >= 0)
      frame.ao[i] = 1.0;
}
}

void RegisterVoxelConesTechnique()
{
  SurfaceTechnique t;
  t.method = 1; // vtkContextualAOPass::VCT
  t.name = "vct";
  t.label = "Voxel Cones";
  t.readsGrid = true;
  t.cpu = [](const cao::PixelCamera&, const SurfaceTechniqueSettings& s, cao::SurfaceFrame& frame,
            std::string& error) {
    if (Unresolved(s))
      return NoAO(frame), true;
    cao::VCTPlan plan;
    return PlanOf(s, plan, error) && cao::VCTFrame(*s.grid, plan, frame, s.threads, error);
  };
  t.gpu = [](SceneGPU& gpu, const cao::PixelCamera&, const SurfaceTechniqueSettings& s, cao::SurfaceFrame& frame,
            std::string& error) {
    // On the grid voxelized (or uploaded) last, the volumes uploaded.
    if (Unresolved(s))
      return NoAO(frame), true;
    cao::VCTPlan plan;
    cao::gl::VCTEngine* cones = gpu.Cones(error);
    double ms = 0.0;
    return cones && PlanOf(s, plan, error) && cones->TraceFrame(*s.grid, plan, frame, ms, error);
  };
  t.gpuFrame = [](SceneGPU& gpu, const cao::PixelCamera&, const SurfaceTechniqueSettings& s, std::string& error) {
    cao::VCTPlan plan;
    cao::gl::VCTEngine* cones = gpu.Cones(error);
    if (!cones || !PlanOf(s, plan, error))
      return false;
    if (Unresolved(s))
      plan.spheres.clear(); // (no sphere: the shader gives the covered pixels no AO, 1)
    return
      gpu.FrameAOStep(nullptr, [&](cao::gl::FrameEngine& f, std::string& e) {
        double ms = 0.0;
        return cones->TracePixels(
          plan, f.PointBuffer(), f.NormalBuffer(), f.AOBuffer(), f.Pixels(), ms, e, f.Width());
      }, error);
  };
  RegisterBuiltIn(t);
}
}
