/**
 * caoBenchPlot — the accuracy-versus-time chart of a benchmark: one point
 * per configuration (its time and its AO error), drawn on log-log axes
 * with VTK's charts (vtkChartXY in a vtkContextView) and written to a PNG
 * without a display: an offscreen X window when DISPLAY is set, else the
 * project's EGL window, as `cao render` does. The Pareto front (the
 * configurations that no other one beats on both time and error) is drawn
 * as a line, its points ringed, and every point carries its label.
 */
#ifndef caoBenchPlot_h
#define caoBenchPlot_h

#include <cstddef>
#include <string>
#include <vector>

namespace caocli
{
struct PlotPoint
{
  double time = 0;   // x, milliseconds, > 0
  double error = 0;  // y, > 0 (RMSE of AO)
  std::string label; // short label drawn next to the point, e.g. "26 M8 rot"
  int series = 0;    // index into seriesNames: points of one series share a colour/marker
};

/// Indices of the Pareto-optimal points (no other point has time <= and
/// error <= with one strictly less), sorted by time (then error, then index).
std::vector<std::size_t> ParetoFront(const std::vector<PlotPoint>& points);

/**
 * Draw error against time on log-log axes: one marker style and colour per
 * series (the legend shows seriesNames), the Pareto front as a thick line
 * through its points sorted by time ("Pareto front" in the legend), its
 * points ringed, and every point labelled next to its marker. Writes a PNG
 * of width x height to pngPath. Returns false with a message in `error`
 * (nothing thrown) when the input is invalid (no points, a time or error
 * that is not a positive finite number, a series without a name, a bad
 * size), when no OpenGL context can be had, or when the PNG cannot be
 * written.
 */
bool WriteErrorTimePlot(const std::vector<PlotPoint>& points,
  const std::vector<std::string>& seriesNames, const std::string& title, const std::string& xTitle,
  const std::string& yTitle, const std::string& pngPath, int width, int height,
  std::string& error);
}

#endif
