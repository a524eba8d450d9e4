/**
 * caoBenchLines — `cao bench lines`: what line AO's accuracy costs in time,
 * against the ray-traced reference on the exact tubes and beside
 * vtkSSAOPass on the same tubes. For each line file (one scene), from one
 * camera and a second turned by a small orbit: line AO at each half ball,
 * sample count and slice count, vtkSSAOPass at each kernel size, and no
 * AO, each with its RMSE, signed bias, p99, the rank correlation of the
 * lines' mean AO with the reference's, the mean frame-to-frame change
 * under the orbit beside the reference's own, and its time. Writes
 * DIR/lines.csv, DIR/lines.json and DIR/lines.png (error against time,
 * log-log, the Pareto front marked), and prints the table.
 */
#ifndef caoBenchLines_h
#define caoBenchLines_h

#include "caoOptions.h"

namespace caocli
{
/// Adds `cao bench lines` under `bench`.
Command AddBenchLinesCommand(CLI::App& bench);
}

#endif
