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

namespace caocli
{
/// The usage text of `cao bench accuracy`.
extern const char* BenchUsage;

/// `cao bench accuracy VOLUME [options]`; returns the process exit code.
int RunBench(int argc, char* argv[]);
}

#endif
