/**
 * caoBenchSurface — `cao bench surface`: what surface AO accuracy costs in
 * time. On each mesh, from one camera (and a second turned by a small
 * orbit, for flicker), every method and preset (voxel cone tracing at each
 * quality and grid size, horizon-based AO at the paper's configurations,
 * volumetric AO at its qualities, vtkSSAOPass at several kernel sizes, no
 * AO) is
 * timed and compared with the ray-traced reference: RMSE, signed bias,
 * p99, the RMSE in a band around depth discontinuities, and the mean frame
 * to frame change under the orbit beside the reference's own. The
 * reference's own error is estimated against 4 times the rays. Writes
 * DIR/surface.csv, DIR/surface.json and DIR/surface.png (error against
 * time, log-log, the Pareto front marked).
 */
#ifndef caoBenchSurface_h
#define caoBenchSurface_h

#include "caoOptions.h"

namespace caocli
{
/// Adds `cao bench surface` under `bench` (the `cao bench` app). Its options are bound to
/// options the command owns; run() runs it after the parse (the exit code).
Command AddBenchSurfaceCommand(CLI::App& bench);
}

#endif
