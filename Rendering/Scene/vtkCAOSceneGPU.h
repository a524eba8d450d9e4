/**
 * vtkCAOSceneGPU — private: vtkContextualAOPass's GPU path, in the render
 * window's own OpenGL context (the pass runs inside the window's render,
 * its context current), or in a headless context of its own for a caller
 * that renders nothing itself (`cao surface`: ResolveHeadless): voxel cone tracing's grid and cones
 * (cao::gl::VCTEngine) and the screen-space methods' estimators
 * (cao::gl::ScreenAOEngine) and line AO's rays or prisms
 * (cao::gl::LineAOEngine) of the VTK-free GL layer, whose state guard
 * gives VTK's GL state back as it was. Backend choice as the filters'
 * (vtkCAOGPUSession.h): CPU never touches OpenGL; OpenGL needs the window's
 * OpenGL 4.3 (else an error); Auto uses it on a hardware GPU and the CPU
 * with a software rasteriser (llvmpipe: slower than the CPU kernels) or
 * without OpenGL 4.3, saying why in Note. Not wrapped, not installed.
 */
#ifndef vtkCAOSceneGPU_h
#define vtkCAOSceneGPU_h

#include "caoLineAO.h"
#include "caoScreenSpaceAO.h"
#include "caoVoxelConeTracing.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

class vtkRenderWindow;
class vtkWindow;

namespace cao
{
namespace gl
{
class FrameEngine;
class ScreenAOEngine;
class VCTEngine;
}
}

namespace vtkCAO
{
class SceneGPU
{
public:
  SceneGPU();
  ~SceneGPU();
  SceneGPU(const SceneGPU&) = delete;
  SceneGPU& operator=(const SceneGPU&) = delete;

  /// Whether this frame's VCT runs on `window`'s OpenGL (backend: 0 Auto,
  /// 1 CPU, 2 OpenGL). False and `error` set when OpenGL was asked for and
  /// cannot be had; false with Note set when Auto chose the CPU.
  bool Resolve(vtkRenderWindow* window, int backend, std::string& error);
  /// The same without a window, on a headless OpenGL context of its own
  /// (EGL or OSMesa, cao::gl::Context::CreateHeadless), for a caller that
  /// renders nothing itself (`cao surface`): it runs the techniques' GPU
  /// steps as the pass does. Made once; a window's Resolve drops it.
  bool ResolveHeadless(int backend, std::string& error);
  /// cao::gl::VCTEngine::Voxelize into `grid`'s place (its bits stay on the GPU).
  /// `surfaceVoxels`: the meshes' surface voxels set with the parity fill
  /// (cao::FillGrid's).
  bool Voxelize(cao::BitGrid& grid, const std::vector<cao::MeshView>& meshes, std::string& error,
    bool surfaceVoxels = true);
  /// cao::gl::VCTEngine::Upload: a grid made on the CPU, traced next.
  bool Upload(const cao::BitGrid& grid, std::string& error);
  /// cao::gl::VCTEngine::Read: the grid's bits (Voxelize's) into `grid.bits`.
  bool Read(cao::BitGrid& grid, std::string& error);
  /// cao::gl::VCTEngine::UploadVolumes: the volumes' opacity for the plans
  /// that name them (again whenever it was rebuilt); FitsVolumes: whether
  /// `count` volumes of `voxels` voxels in all fit its limits here.
  bool Volumes(const std::vector<const cao::OpacityVolume*>& volumes, std::string& error);
  bool FitsVolumes(long long voxels, long long count, std::string& error);
  ///@{
  /// The GL layer's engines in the window's context, for the surface
  /// techniques' GPU steps (vtkCAOSurfaceTechnique.h: each technique's file
  /// calls its own engine, so a new technique adds no entry point here):
  /// the grid and the cones (holding the grid voxelized last and the
  /// volumes uploaded), the screen-space estimators. Null with `error` until
  /// Resolve chose the GPU.
  cao::gl::VCTEngine* Cones(std::string& error);
  cao::gl::ScreenAOEngine* ScreenAO(std::string& error);
  ///@}
  /// A GPU frame step of a technique: `step` writes the AO of the GPU
  /// frame's pixels from its G-buffer (FrameGBuffer's points and normals)
  /// into its AO buffer, read by FrameCombine and FrameAO; `camera` (when
  /// given) must be the frame's image.
  bool FrameAOStep(const cao::PixelCamera* camera,
    const std::function<bool(cao::gl::FrameEngine& frame, std::string& error)>& step, std::string& error);
  /// cao::gl::LineAOEngine::Voxelize: cao::VoxelizeLines' twin into
  /// `grid`'s plan; the bits stay on the GPU for LineAO given a grid of
  /// that plan with no bits.
  /// With `segmentDrawing` the lines go to the GPU once per `version`
  /// (LineAOEngine::SetLines) and are mapped into the grid there.
  bool VoxelizeLines(const cao::BitGrid& grid, const cao::LineSegments& lines, double tubeRadius,
    std::string& error, std::uint64_t version = 0, const std::vector<std::int32_t>* segmentDrawing = nullptr);
  /// cao::gl::LineAOEngine::Frame: cao::LineAOFrame's twin (the lines'
  /// G-buffer made on the CPU, the prisms counted on the GPU, in the grid
  /// VoxelizeLines left there when `grid` has no bits).
  bool LineAO(const cao::BitGrid& grid, const cao::LineAOSettings& settings, cao::LineFrame& frame,
    const cao::BitGrid* solids, std::string& error);
  /// The bits VoxelizeLines left on the GPU, into `grid.bits`.
  bool ReadLineGrid(cao::BitGrid& grid, std::string& error);
  /// The GPU time (ms, the shaders') of the last VoxelizeLines, LineGBuffer
  /// and LineAO or LineAOOfGBuffer, in that order.
  const double* LineMilliseconds() const { return this->lineMs; }
  /// cao::gl::LineAOEngine::LineGBuffer and FrameOfLineGBuffer: the lines'
  /// G-buffer from the drawn depth with no search on the CPU (each segment
  /// visits the drawn pixels within its reach), then the prisms, on the GPU.
  /// `version` names `lines` (uploaded when it changes).
  bool LineGBuffer(const cao::BitGrid& grid, const cao::LineAOSettings& settings, const cao::LineSegments& lines,
    std::uint64_t version, const std::vector<cao::LineDrawing>& drawings,
    const std::vector<std::int32_t>& segmentDrawing, const cao::PixelCamera& camera, const std::vector<float>& depth,
    const std::vector<unsigned char>* skip, std::string& error);
  bool LineAOOfGBuffer(const cao::BitGrid& grid, const cao::LineAOSettings& settings, cao::LineFrame& frame,
    const cao::BitGrid* solids, std::string& error);
  ///@{
  /// The frame kept on the GPU (cao::gl::FrameEngine; the depth G-buffer;
  /// VCT, HBAO, volumetric AO without indirect light): the drawn depth of `framebuffer`'s rectangle (x0, y0,
  /// width, height) read on the GPU and its pixels that changed since the
  /// last G-buffer counted; the G-buffer (`ndcToWorld` row-major, into
  /// `grid`'s frame), its covered pixels counted; the cones on the grid
  /// voxelized last; the drawn colour (or the ambient drawing) read; the
  /// combine written into `framebuffer`. FrameAO reads the AO back (making
  /// the window's context current if it is not).
  bool FrameDepth(unsigned framebuffer, const int rect[4], std::int64_t& changed, std::string& error);
  bool FrameGBuffer(const double ndcToWorld[16], const cao::BitGrid& grid, std::int64_t& covered,
    std::string& error);
  bool FrameRead(bool ambient, unsigned framebuffer, const int rect[4], std::string& error);
  bool FrameCombine(double strength, bool wholeColor, unsigned framebuffer, const int rect[4], std::string& error);
  bool FrameAO(std::vector<float>& ao, std::string& error);
  /// The lines' combine on the GPU: `ao` (one float per pixel of the
  /// rectangle, NaN where nothing is darkened) on the drawn colour of
  /// `framebuffer`'s rectangle, colour (1 - strength (1 - AO)), written
  /// back there (FrameEngine: depth and colour blitted, SetAO, Combine,
  /// Write); no pixel comes back to the host.
  bool FrameCombineAO(const std::vector<float>& ao, double strength, unsigned framebuffer, const int rect[4],
    std::string& error);
  /// "blit" or "read": how the GPU frame's depth came (FrameEngine::DepthBlitted).
  std::string FrameDepthPath() const;
  ///@}
  /// "OpenGL (renderer, version)" once resolved to the GPU.
  std::string Description() const;
  /// GPU memory held (bytes).
  long long ResidentBytes() const;
  /// Engines made so far: a new one (a new window, or after Release) holds
  /// no grid, so the pass keys its grid on it.
  int Generation() const;
  /// The pass's ReleaseGraphicsResources for `window`: the GL objects are
  /// deleted when their window's context is current, else forgotten (no
  /// context is made current or created); another window's call is ignored.
  void Release(vtkWindow* window);

  std::string Note; ///< why Auto chose the CPU (empty otherwise)

private:
  /// After a Resolve: whether the context is there and, for Auto, not a
  /// software rasteriser; else the error (OpenGL asked for) or the Note.
  bool Usable(int backend, std::string& error);
  struct Impl;
  std::unique_ptr<Impl> P;
  double lineMs[3] = { 0.0, 0.0, 0.0 };
};
}

#endif
