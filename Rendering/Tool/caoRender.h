/**
 * caoRender — `cao render`: PNG frames of a clip shape moving through a
 * volume, drawn by vtkContextualAOVolumeMapper with contextual AO updated
 * at every pose, in an offscreen window (EGL without a display, X with
 * one), with a transfer function from a ParaView .json preset or a
 * built-in one. --json prints each frame's work report.
 */
#ifndef caoRender_h
#define caoRender_h

#include "caoOptions.h"

namespace caocli
{
/// Adds `cao render` under `cao` (the root app). Its options are bound to
/// options the command owns; run() runs it after the parse (the exit code).
Command AddRenderCommand(CLI::App& cao);
}

#endif
