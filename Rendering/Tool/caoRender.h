/**
 * caoRender — `cao render`: PNG frames of a clip shape moving through a
 * volume, drawn by vtkContextualAOVolumeMapper with contextual AO updated
 * at every pose, in an offscreen window (EGL without a display, X with
 * one), with a transfer function from a ParaView .json preset or a
 * built-in one. --json prints each frame's work report.
 */
#ifndef caoRender_h
#define caoRender_h

namespace caocli
{
extern const char* RenderUsage;
/// argv[1] is "render". Exit codes as the rest of `cao`.
int RunRender(int argc, char* argv[]);
}

#endif
