/**
 * caoBenchSurfaceFrame — `cao bench surface-frame`: whole VTK frames of the
 * product's pass (vtkContextualAOPass) against vtkSSAOPass and a plain frame,
 * in the same offscreen window, at the same size and radius, side by side
 * in one run. The camera turns a little every frame (so each method
 * computes its AO again, as under an interaction) and then stands still
 * (the pass only combines); each frame waits for the GPU (a one-pixel read
 * back). Per pass configuration it prints where the time goes (the pass's
 * own stage report). Time only: the accuracy is `cao bench surface`'s.
 */
#ifndef caoBenchSurfaceFrame_h
#define caoBenchSurfaceFrame_h

#include "caoOptions.h"

namespace caocli
{
/// Adds `cao bench surface-frame` under `bench` (the `cao bench` app). Its options are bound to
/// options the command owns; run() runs it after the parse (the exit code).
Command AddBenchSurfaceFrameCommand(CLI::App& bench);
}

#endif
