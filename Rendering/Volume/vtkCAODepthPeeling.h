/**
 * vtkCAODepthPeeling — what a host's dual depth peeling asks of the
 * contextual-AO volume mapper (private to ContextualAO::RenderingVolume).
 *
 * With translucent geometry in the view and the renderer's
 * UseDepthPeelingForVolumes (ParaView's "Depth Peeling For Volumes", on by
 * default), VTK draws volumes inside vtkDualDepthPeelingPass, several times a
 * frame, into framebuffers without a depth attachment; the pass tells its
 * own volume mapper which stage it is in and where its textures are through
 * shader substitutions and uniforms. This reads the same two channels
 * without drawing: the stage from the code the pass substitutes into a
 * template, and the texture units from a probe program whose uniforms the
 * pass sets, then the texture names bound on those units.
 */
#ifndef vtkCAODepthPeeling_h
#define vtkCAODepthPeeling_h

#include <string>

class vtkAbstractVolumeMapper;
class vtkRenderer;
class vtkVolume;

namespace vtkCAO
{
struct PeelState
{
  int stage = 0; // 0: not peeling; else CAO_PEEL_OUTSIDE, _LAYER or _REMAINDER
  unsigned int outer = 0, inner = 0, front = 0, opaque = 0; // GL texture names
};

/// Whether `volume` is being drawn inside a dual depth peeling pass and,
/// if so, in which stage and with which textures. False with `error` set
/// when a peeling pass is present but its state cannot be read.
bool QueryDepthPeeling(vtkRenderer* renderer, vtkVolume* volume, vtkAbstractVolumeMapper* mapper,
  PeelState& state, std::string& error);
}

#endif
