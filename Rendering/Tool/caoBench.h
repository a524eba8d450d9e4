/**
 * caoBench — `cao bench accuracy`: what accuracy costs in time.
 *
 * Sweeps the LAO's ray pattern, sample density (samples per voxel, hence
 * the step), ray variation and start offset, and the AO's storage
 * precision, and, for the contextual update, the clipping camera's
 * depth-map resolution. Every configuration is timed on each available
 * backend and measured against a reference AO (caoReference: 2 x 4096
 * stratified directions, steps of at most 1/4 voxel, double) over the
 * visible voxels, and, through the volume mapper, against a frame rendered
 * with the reference AO (PSNR). Writes accuracy.csv, accuracy.json and
 * accuracy.png (error against time, log-log, the Pareto front marked).
 */
#ifndef caoBench_h
#define caoBench_h

#include "caoOptions.h"

namespace caocli
{

/// Adds `cao bench accuracy` under `bench` (the `cao bench` app). Its options are bound to
/// options the command owns; run() runs it after the parse (the exit code).
Command AddBenchAccuracyCommand(CLI::App& bench);
}

#endif
