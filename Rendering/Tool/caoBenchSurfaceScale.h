/**
 * caoBenchSurfaceScale — `cao bench surface-scale`: how the cost of surface
 * AO grows with pixels and triangles, side by side with vtkSSAOPass in one
 * run. The meshes are tiled into 1, 9, 81 ... copies (the design's "many
 * instances of the CAD part"); at each image size it times, per frame, the
 * G-buffer cast, the world grid (once per geometry), the eye grid (again at
 * each camera turn), the cone tracing, horizon-based and volumetric AO at
 * their default presets on the same G-buffer, and vtkSSAOPass at its
 * default kernel; it prints the table with the ratios to vtkSSAOPass and writes
 * DIR/surface-scale.csv. Time only: the accuracy is `cao bench surface`'s.
 */
#ifndef caoBenchSurfaceScale_h
#define caoBenchSurfaceScale_h

#include "caoOptions.h"

namespace caocli
{
/// Adds `cao bench surface-scale` under `bench` (the `cao bench` app). Its options are bound to
/// options the command owns; run() runs it after the parse (the exit code).
Command AddBenchSurfaceScaleCommand(CLI::App& bench);
}

#endif
