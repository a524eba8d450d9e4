/**
 * caoBenchPlot — see caoBenchPlot.h. The chart is VTK's own: a vtkChartXY
 * with log-scaled axes in a vtkContextView whose render window is an
 * offscreen one (X with a display, else EGL), drawn at twice the size and
 * averaged down (smooth lines without multisampling). vtkPlotPoints draws
 * no text next to its markers, so the point labels come from a context
 * item of this file painted over the chart: it maps each point through the
 * chart's axes (log10 where the axis is log scaled, as the plots do) and
 * places its label beside the marker where it hides no other marker,
 * label, the legend or the front line, if it can.
 */
#include "caoBenchPlot.h"
#include "caoWindow.h"

#include "vtkAxis.h"
#include "vtkBrush.h"
#include "vtkChartLegend.h"
#include "vtkChartXY.h"
#include "vtkContext2D.h"
#include "vtkContextItem.h"
#include "vtkContextScene.h"
#include "vtkContextView.h"
#include "vtkDoubleArray.h"
#include "vtkImageShrink3D.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPNGWriter.h"
#include "vtkPen.h"
#include "vtkPlotLine.h"
#include "vtkPlotPoints.h"
#include "vtkRect.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"
#include "vtkTable.h"
#include "vtkTextProperty.h"
#include "vtkWindowToImageFilter.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

namespace caocli
{
namespace
{
// Series colours (Okabe-Ito, without the red of the front and the yellow
// that is unreadable on white), then marker shapes, cycled.
const unsigned char SeriesColors[][3] = { { 0, 114, 178 }, { 230, 159, 0 }, { 0, 158, 115 },
  { 204, 121, 167 }, { 86, 180, 233 }, { 110, 110, 110 }, { 140, 86, 45 } };
const int SeriesMarkers[] = { vtkPlotPoints::CIRCLE, vtkPlotPoints::SQUARE,
  vtkPlotPoints::DIAMOND };
const unsigned char FrontColor[3] = { 200, 30, 45 };

// Sizes in pixels of the written image.
const float MarkerSize = 10.f; // series markers
const float RingOuter = 21.f;  // the ring around a front point: outer and
const float RingInner = 15.f;  // inner diameters
const int LabelFontSize = 12;  // points, at 72 dpi: pixels

struct Box
{
  float x0, y0, x1, y1;
  float Area() const { return std::max(0.f, x1 - x0) * std::max(0.f, y1 - y0); }
};

float Overlap(const Box& a, const Box& b)
{
  return Box{ std::max(a.x0, b.x0), std::max(a.y0, b.y0), std::min(a.x1, b.x1),
    std::min(a.y1, b.y1) }
    .Area();
}

// Whether the segment p-q crosses the box (Liang-Barsky clipping).
bool SegmentHitsBox(float px, float py, float qx, float qy, const Box& b)
{
  float t0 = 0.f, t1 = 1.f;
  const float dx = qx - px, dy = qy - py;
  const float p[4] = { -dx, dx, -dy, dy };
  const float q[4] = { px - b.x0, b.x1 - px, py - b.y0, b.y1 - py };
  for (int i = 0; i < 4; ++i)
  {
    if (p[i] == 0.f)
    {
      if (q[i] < 0.f)
        return false;
      continue;
    }
    const float t = q[i] / p[i];
    if (p[i] < 0.f)
      t0 = std::max(t0, t);
    else
      t1 = std::min(t1, t);
    if (t0 > t1)
      return false;
  }
  return true;
}

/**
 * What the chart does not draw itself: the point labels, and the axis
 * titles (VTK puts those a fixed number of pixels from the tick labels,
 * which is too close in the supersampled image; the axes keep their titles
 * so that the layout leaves room, but do not draw them). Painted after the
 * chart, in scene coordinates. Each point goes through the chart's bottom
 * and left axes as the plots' own transform takes it (log10 of the value
 * where the axis is log scaled, then the axis' range onto its two end
 * points), and its label takes the first of a few places around the
 * marker that covers nothing else.
 */
class ChartOverlay : public vtkContextItem
{
public:
  static ChartOverlay* New();
  vtkTypeMacro(ChartOverlay, vtkContextItem);

  struct Entry
  {
    double x, y;
    std::string text;
    bool front;
  };
  std::vector<Entry> Entries;
  vtkChartXY* Chart = nullptr; // the chart owns nothing of this; both live in one scene
  float Scale = 1.f;           // pixels per output pixel (the image is drawn supersampled)

  bool Paint(vtkContext2D* painter) override;

protected:
  void PaintAxisTitle(vtkContext2D* painter, vtkAxis* axis, bool vertical);

  ChartOverlay() = default;
  ~ChartOverlay() override = default;

private:
  ChartOverlay(const ChartOverlay&) = delete;
  void operator=(const ChartOverlay&) = delete;
};
vtkStandardNewMacro(ChartOverlay);

// Data value to scene coordinate along one axis (dim 0: x, 1: y).
float ToScene(vtkAxis* axis, double value, int dim)
{
  const double v = axis->GetLogScaleActive() ? std::log10(value) : value;
  const double lo = axis->GetMinimum(), hi = axis->GetMaximum();
  const float* p1 = axis->GetPoint1();
  const float* p2 = axis->GetPoint2();
  const double t = hi != lo ? (v - lo) / (hi - lo) : 0.5;
  return static_cast<float>(p1[dim] + t * (p2[dim] - p1[dim]));
}

// Where VTK would put the axis title, but a few pixels farther from the
// tick labels (in the room that the axis' margin leaves).
void ChartOverlay::PaintAxisTitle(vtkContext2D* painter, vtkAxis* axis, bool vertical)
{
  const std::string title = axis->GetTitle();
  if (title.empty())
    return;
  float bounds[4];
  float widest = 0.f, tallest = 0.f;
  if (vtkStringArray* ticks = axis->GetTickLabels())
  {
    painter->ApplyTextProp(axis->GetLabelProperties());
    for (vtkIdType i = 0; i < ticks->GetNumberOfValues(); ++i)
    {
      painter->ComputeStringBounds(ticks->GetValue(i), bounds);
      widest = std::max(widest, bounds[2]);
      tallest = std::max(tallest, bounds[3]);
    }
  }
  vtkNew<vtkTextProperty> text;
  text->ShallowCopy(axis->GetTitleProperties());
  text->SetOrientation(0.0);
  text->SetJustificationToCentered();
  text->SetVerticalJustificationToCentered();
  painter->ApplyTextProp(text);
  painter->ComputeStringBounds(title, bounds);
  const float height = bounds[3], gap = 6.f * this->Scale;
  const float* p1 = axis->GetPoint1();
  const float* p2 = axis->GetPoint2();
  if (vertical)
  {
    text->SetOrientation(90.0);
    painter->ApplyTextProp(text);
    painter->DrawString(p1[0] - axis->GetLabelOffset() - widest - gap - 0.5f * height,
      0.5f * (p1[1] + p2[1]), title);
  }
  else
    painter->DrawString(0.5f * (p1[0] + p2[0]),
      p1[1] - axis->GetLabelOffset() - tallest - gap - 0.5f * height, title);
}

bool ChartOverlay::Paint(vtkContext2D* painter)
{
  if (!this->Chart)
    return true;
  this->PaintAxisTitle(painter, this->Chart->GetAxis(vtkAxis::BOTTOM), false);
  this->PaintAxisTitle(painter, this->Chart->GetAxis(vtkAxis::LEFT), true);
  if (this->Entries.empty())
    return true;
  const float s = this->Scale;
  const float marker = s * MarkerSize, ring = s * RingOuter;
  vtkAxis* xAxis = this->Chart->GetAxis(vtkAxis::BOTTOM);
  vtkAxis* yAxis = this->Chart->GetAxis(vtkAxis::LEFT);
  const Box plot{ xAxis->GetPoint1()[0], yAxis->GetPoint1()[1], xAxis->GetPoint2()[0],
    yAxis->GetPoint2()[1] };

  // What a label should not cover: the markers (rings included), the
  // legend, the front line; and what it must stay inside: the plot area.
  const std::size_t n = this->Entries.size();
  std::vector<float> sx(n), sy(n);
  std::vector<Box> obstacles;
  for (std::size_t i = 0; i < n; ++i)
  {
    sx[i] = ToScene(xAxis, this->Entries[i].x, 0);
    sy[i] = ToScene(yAxis, this->Entries[i].y, 1);
    const float r = 0.5f * (this->Entries[i].front ? ring : marker) + s;
    obstacles.push_back(Box{ sx[i] - r, sy[i] - r, sx[i] + r, sy[i] + r });
  }
  vtkChartLegend* legend = this->Chart->GetLegend();
  if (legend && legend->GetVisible())
  {
    const vtkRectf l = legend->GetBoundingRect(painter);
    obstacles.push_back(
      Box{ l.GetX(), l.GetY(), l.GetX() + l.GetWidth(), l.GetY() + l.GetHeight() });
  }
  std::vector<std::array<float, 4>> segments;
  {
    std::vector<std::size_t> front;
    for (std::size_t i = 0; i < n; ++i)
      if (this->Entries[i].front)
        front.push_back(i);
    std::sort(front.begin(), front.end(),
      [&](std::size_t a, std::size_t b) { return sx[a] < sx[b]; });
    for (std::size_t k = 1; k < front.size(); ++k)
      segments.push_back({ sx[front[k - 1]], sy[front[k - 1]], sx[front[k]], sy[front[k]] });
  }

  vtkNew<vtkTextProperty> text;
  text->SetFontFamilyToArial();
  text->SetFontSize(LabelFontSize);
  text->SetJustificationToLeft();
  text->SetVerticalJustificationToCentered();
  text->SetOrientation(0.0);
  text->SetColor(0.12, 0.12, 0.12);
  text->SetOpacity(1.0);
  painter->ApplyTextProp(text);
  float bounds[4];
  painter->ComputeStringBounds("Tgyf", bounds);
  const float lineHeight = bounds[3];
  const float pad = 2.f * s;

  // Front points first (their labels matter most), then the rest by x.
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i)
    order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    if (this->Entries[a].front != this->Entries[b].front)
      return this->Entries[a].front;
    return sx[a] < sx[b];
  });

  struct Placed
  {
    Box box;
    float tx, ty; // where the text goes (left end, vertical centre)
    bool leader;
    std::size_t index;
  };
  std::vector<Placed> placed;
  for (std::size_t i : order)
  {
    const Entry& e = this->Entries[i];
    if (e.text.empty())
      continue;
    text->SetBold(e.front);
    painter->ApplyTextProp(text);
    painter->ComputeStringBounds(e.text, bounds);
    const float w = bounds[2] + 2 * pad, h = std::max(bounds[3], lineHeight) + 2 * pad;
    const float r = 0.5f * (e.front ? ring : marker);

    // Candidate boxes around the marker: right, left, the four diagonals,
    // above, below; then the same farther out (with a leader line). The
    // first that covers nothing wins, else the one that covers least.
    Placed best{};
    float bestCost = std::numeric_limits<float>::max();
    for (int far = 0; far < 3 && bestCost > 0.f; ++far)
    {
      const float g = r + pad + far * (h + pad);
      const float d = 0.72f * g;
      const float cx[8] = { sx[i] + g, sx[i] - g - w, sx[i] + d, sx[i] + d, sx[i] - d - w,
        sx[i] - d - w, sx[i] - 0.5f * w, sx[i] - 0.5f * w };
      const float cy[8] = { sy[i] - 0.5f * h, sy[i] - 0.5f * h, sy[i] + d, sy[i] - d - h, sy[i] + d,
        sy[i] - d - h, sy[i] + g, sy[i] - g - h };
      for (int c = 0; c < 8 && bestCost > 0.f; ++c)
      {
        const Box b{ cx[c], cy[c], cx[c] + w, cy[c] + h };
        // Out of the plot area weighs most (it would cover the axes), then
        // markers, legend and labels, then crossing the front line.
        float cost = 20.f * (b.Area() - Overlap(b, plot));
        for (std::size_t k = 0; k < obstacles.size(); ++k)
          if (k != i)
            cost += 4.f * Overlap(b, obstacles[k]);
        for (const Placed& p : placed)
          cost += 4.f * Overlap(b, p.box);
        for (const auto& seg : segments)
          if (SegmentHitsBox(seg[0], seg[1], seg[2], seg[3], b))
            cost += 0.15f * b.Area();
        if (cost > 0.f)
          cost += 0.1f * far * b.Area(); // among imperfect places, the nearer
        if (cost < bestCost)
        {
          bestCost = cost;
          best = Placed{ b, b.x0 + pad, 0.5f * (b.y0 + b.y1), far > 0, i };
        }
      }
    }
    placed.push_back(best);
  }

  // Leader lines, then a translucent white backing under each label (so
  // grid lines and the front line do not cross the text), then the text.
  painter->GetPen()->SetColor(120, 120, 120, 255);
  painter->GetPen()->SetWidth(s);
  painter->GetPen()->SetLineType(vtkPen::SOLID_LINE);
  for (const Placed& p : placed)
  {
    if (!p.leader)
      continue;
    const float qx = std::min(std::max(sx[p.index], p.box.x0), p.box.x1);
    const float qy = std::min(std::max(sy[p.index], p.box.y0), p.box.y1);
    const float dx = qx - sx[p.index], dy = qy - sy[p.index];
    const float len = std::sqrt(dx * dx + dy * dy);
    const float r = 0.5f * (this->Entries[p.index].front ? ring : marker);
    if (len > r)
      painter->DrawLine(sx[p.index] + dx * r / len, sy[p.index] + dy * r / len, qx, qy);
  }
  painter->GetPen()->SetLineType(vtkPen::NO_PEN);
  painter->GetBrush()->SetColor(255, 255, 255, 215);
  for (const Placed& p : placed)
    painter->DrawRect(p.box.x0, p.box.y0, p.box.x1 - p.box.x0, p.box.y1 - p.box.y0);
  painter->GetPen()->SetLineType(vtkPen::SOLID_LINE);
  for (const Placed& p : placed)
  {
    text->SetBold(this->Entries[p.index].front);
    painter->ApplyTextProp(text);
    painter->DrawString(p.tx, p.ty, this->Entries[p.index].text);
  }
  return true;
}

vtkSmartPointer<vtkTable> MakeTable(const std::vector<double>& x, const std::vector<double>& y)
{
  vtkNew<vtkDoubleArray> xs, ys;
  xs->SetName("time");
  ys->SetName("error");
  for (std::size_t i = 0; i < x.size(); ++i)
  {
    xs->InsertNextValue(x[i]);
    ys->InsertNextValue(y[i]);
  }
  auto table = vtkSmartPointer<vtkTable>::New();
  table->AddColumn(xs);
  table->AddColumn(ys);
  return table;
}

// The axis range: the data's, widened by a margin on the log scale, and
// to a decade at least (so that there are a few ticks to read).
void LogRange(double lo, double hi, double range[2])
{
  const double span = std::log10(hi) - std::log10(lo);
  const double margin = std::max({ 0.07 * span, 0.12, 0.5 * (1.0 - span) });
  range[0] = std::pow(10.0, std::log10(lo) - margin);
  range[1] = std::pow(10.0, std::log10(hi) + margin);
}

void StyleAxis(vtkAxis* axis, const std::string& title, const double range[2], float scale)
{
  axis->SetTitle(title);
  axis->GetTitleProperties()->SetFontSize(16);
  axis->GetTitleProperties()->SetBold(true);
  axis->GetTitleProperties()->SetColor(0.1, 0.1, 0.1);
  axis->GetLabelProperties()->SetFontSize(13);
  axis->GetLabelProperties()->SetColor(0.15, 0.15, 0.15);
  axis->SetLogScale(true);
  axis->SetBehavior(vtkAxis::FIXED);
  axis->SetUnscaledRange(range[0], range[1]);
  // VTK's pixel sizes (5, 7 and 5 pixels), for the supersampled image;
  // the title's margin a little wider (the overlay draws the title).
  axis->SetTickLength(5.f * scale);
  axis->SetLabelOffset(7.f * scale);
  axis->SetMargins(static_cast<int>(20 * scale), static_cast<int>(5 * scale));
  axis->SetTitleVisible(false);
  axis->GetPen()->SetColor(60, 60, 60, 255);
  axis->GetPen()->SetWidth(scale);
  axis->GetGridPen()->SetColor(220, 220, 220, 255);
  axis->GetGridPen()->SetWidth(scale);
}

// Where the legend covers no point: a corner of the plot area, by the
// points' positions as fractions of the (log) axis ranges; else outside
// the plot area, at the right.
void PlaceLegend(vtkChartLegend* legend, const std::vector<PlotPoint>& points,
  const double xRange[2], const double yRange[2], double legendW, double legendH)
{
  const int corners[4][2] = { { vtkChartLegend::LEFT, vtkChartLegend::BOTTOM },
    { vtkChartLegend::RIGHT, vtkChartLegend::TOP },
    { vtkChartLegend::RIGHT, vtkChartLegend::BOTTOM },
    { vtkChartLegend::LEFT, vtkChartLegend::TOP } };
  int best = 0;
  std::size_t bestCount = points.size() + 1;
  for (int c = 0; c < 4; ++c)
  {
    std::size_t count = 0;
    for (const PlotPoint& p : points)
    {
      const double fx = (std::log10(p.time) - std::log10(xRange[0])) /
        (std::log10(xRange[1]) - std::log10(xRange[0]));
      const double fy = (std::log10(p.error) - std::log10(yRange[0])) /
        (std::log10(yRange[1]) - std::log10(yRange[0]));
      const bool inX = corners[c][0] == vtkChartLegend::LEFT ? fx < legendW : fx > 1.0 - legendW;
      const bool inY = corners[c][1] == vtkChartLegend::BOTTOM ? fy < legendH : fy > 1.0 - legendH;
      count += inX && inY ? 1 : 0;
    }
    if (count < bestCount)
    {
      bestCount = count;
      best = c;
    }
  }
  legend->SetInline(bestCount == 0);
  legend->SetHorizontalAlignment(bestCount == 0 ? corners[best][0] : vtkChartLegend::RIGHT);
  legend->SetVerticalAlignment(bestCount == 0 ? corners[best][1] : vtkChartLegend::TOP);
}
}

std::vector<std::size_t> ParetoFront(const std::vector<PlotPoint>& points)
{
  std::vector<std::size_t> front;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    bool dominated = false;
    for (std::size_t j = 0; j < points.size() && !dominated; ++j)
    {
      const PlotPoint &a = points[j], &b = points[i];
      dominated = j != i && a.time <= b.time && a.error <= b.error &&
        (a.time < b.time || a.error < b.error);
    }
    if (!dominated)
      front.push_back(i);
  }
  std::sort(front.begin(), front.end(), [&](std::size_t a, std::size_t b) {
    if (points[a].time != points[b].time)
      return points[a].time < points[b].time;
    if (points[a].error != points[b].error)
      return points[a].error < points[b].error;
    return a < b;
  });
  return front;
}

bool WriteErrorTimePlot(const std::vector<PlotPoint>& points,
  const std::vector<std::string>& seriesNames, const std::string& title, const std::string& xTitle,
  const std::string& yTitle, const std::string& pngPath, int width, int height,
  std::string& error)
{
  // The input.
  if (points.empty())
  {
    error = "nothing to plot: no points";
    return false;
  }
  if (width < 200 || height < 150 || width > 16384 || height > 16384)
  {
    error = "plot size " + std::to_string(width) + "x" + std::to_string(height) +
      " is out of range (200x150 to 16384x16384)";
    return false;
  }
  double tMin = std::numeric_limits<double>::max(), tMax = 0.0;
  double eMin = std::numeric_limits<double>::max(), eMax = 0.0;
  for (const PlotPoint& p : points)
  {
    if (!(std::isfinite(p.time) && p.time > 0.0) || !(std::isfinite(p.error) && p.error > 0.0))
    {
      char v[96];
      std::snprintf(v, sizeof(v), " (time %g, error %g)", p.time, p.error);
      error = "point '" + p.label + "'" + v + ": time and error must be positive and finite";
      return false;
    }
    if (p.series < 0 || static_cast<std::size_t>(p.series) >= seriesNames.size())
    {
      error = "point '" + p.label + "': series " + std::to_string(p.series) + " has no name (" +
        std::to_string(seriesNames.size()) + " series named)";
      return false;
    }
    tMin = std::min(tMin, p.time);
    tMax = std::max(tMax, p.time);
    eMin = std::min(eMin, p.error);
    eMax = std::max(eMax, p.error);
  }
  if (pngPath.empty())
  {
    error = "no PNG path";
    return false;
  }
  // The window: X when there is a display, else EGL (as `cao render`).
  std::string description;
  vtkSmartPointer<vtkRenderWindow> window = MakeOffscreenWindow("auto", description, error);
  if (!window)
    return false;

  // The PNG can be written (before the work, and without VTK's own error
  // message if it cannot).
  if (FILE* f = std::fopen(pngPath.c_str(), "wb"))
    std::fclose(f);
  else
  {
    error = "cannot write '" + pngPath + "'";
    return false;
  }

  // The chart is drawn at twice the size (fonts through the DPI, the rest
  // by `scale`) and averaged down: smooth lines without multisampling,
  // which leaves fringes on VTK's marker sprites.
  const int scale = std::max(width, height) <= 4096 ? 2 : 1;
  const float fs = static_cast<float>(scale);
  vtkNew<vtkContextView> view;
  view->SetRenderWindow(window);
  view->GetRenderer()->SetBackground(1.0, 1.0, 1.0);
  window->SetSize(width * scale, height * scale);
  window->SetDPI(72 * scale);

  // The chart: title, log-log axes, legend, a margin around it all.
  vtkNew<vtkChartXY> chart;
  view->GetScene()->AddItem(chart);
  const float margin = 8.f * fs;
  chart->SetLayoutStrategy(vtkChart::FILL_RECT);
  chart->SetSize(vtkRectf(margin, margin, width * fs - 2 * margin, height * fs - 2 * margin));
  chart->SetHiddenAxisBorder(static_cast<int>(20 * fs));
  chart->SetTitle(title);
  chart->GetTitleProperties()->SetFontSize(20);
  chart->GetTitleProperties()->SetBold(true);
  chart->GetTitleProperties()->SetColor(0.05, 0.05, 0.05);
  double xRange[2], yRange[2];
  LogRange(tMin, tMax, xRange);
  LogRange(eMin, eMax, yRange);
  StyleAxis(chart->GetAxis(vtkAxis::BOTTOM), xTitle, xRange, fs);
  StyleAxis(chart->GetAxis(vtkAxis::LEFT), yTitle, yRange, fs);
  chart->SetShowLegend(true);
  vtkChartLegend* legend = chart->GetLegend();
  legend->GetLabelProperties()->SetFontSize(14);
  legend->GetLabelProperties()->SetColor(0.1, 0.1, 0.1);
  legend->GetBrush()->SetColor(255, 255, 255, 235);
  legend->GetPen()->SetColor(150, 150, 150, 255);
  legend->GetPen()->SetWidth(fs);
  legend->SetPadding(static_cast<int>(5 * fs));
  legend->SetSymbolWidth(static_cast<int>(25 * fs));
  {
    // A rough size of the legend, as fractions of the plot area.
    std::size_t longest = std::string("Pareto front").size();
    for (const std::string& n : seriesNames)
      longest = std::max(longest, n.size());
    const double w = (8.0 * longest + 50.0) / std::max(1, width - 150);
    const double h = (22.0 * (seriesNames.size() + 1) + 10.0) / std::max(1, height - 130);
    PlaceLegend(legend, points, xRange, yRange, w, h);
  }

  // The front: a thick line under everything, then rings under its points.
  const std::vector<std::size_t> front = ParetoFront(points);
  std::vector<bool> onFront(points.size(), false);
  std::vector<double> fx, fy;
  for (std::size_t i : front)
  {
    onFront[i] = true;
    fx.push_back(points[i].time);
    fy.push_back(points[i].error);
  }
  vtkSmartPointer<vtkTable> frontTable = MakeTable(fx, fy);
  // A line needs two points: a front of one gets a line of length zero
  // (and keeps its legend entry).
  vtkSmartPointer<vtkTable> lineTable = front.size() > 1
    ? frontTable
    : MakeTable({ fx[0], fx[0] }, { fy[0], fy[0] });
  auto* line = vtkPlotLine::SafeDownCast(chart->AddPlot(vtkChart::LINE));
  line->SetInputData(lineTable, 0, 1);
  line->SetColor(FrontColor[0], FrontColor[1], FrontColor[2], 255);
  line->SetWidth(3.f * fs);
  line->SetMarkerStyle(vtkPlotPoints::NONE);
  line->SetLabel("Pareto front");
  const float rings[2] = { RingOuter, RingInner };
  for (int k = 0; k < 2; ++k)
  {
    auto* ring = vtkPlotPoints::SafeDownCast(chart->AddPlot(vtkChart::POINTS));
    ring->SetInputData(frontTable, 0, 1);
    if (k == 0)
      ring->SetColor(FrontColor[0], FrontColor[1], FrontColor[2], 255);
    else
      ring->SetColor(255, 255, 255, 255);
    ring->SetMarkerStyle(vtkPlotPoints::CIRCLE);
    ring->SetMarkerSize(rings[k] * fs);
    ring->SetLegendVisibility(false);
  }

  // The series, one plot each (a series without points gets none).
  const std::size_t nc = sizeof(SeriesColors) / sizeof(SeriesColors[0]);
  const std::size_t nm = sizeof(SeriesMarkers) / sizeof(SeriesMarkers[0]);
  for (std::size_t s = 0; s < seriesNames.size(); ++s)
  {
    std::vector<double> x, y;
    for (const PlotPoint& p : points)
      if (static_cast<std::size_t>(p.series) == s)
      {
        x.push_back(p.time);
        y.push_back(p.error);
      }
    if (x.empty())
      continue;
    auto* plot = vtkPlotPoints::SafeDownCast(chart->AddPlot(vtkChart::POINTS));
    plot->SetInputData(MakeTable(x, y), 0, 1);
    plot->SetColor(SeriesColors[s % nc][0], SeriesColors[s % nc][1], SeriesColors[s % nc][2], 255);
    plot->SetMarkerStyle(SeriesMarkers[s % nm]);
    plot->SetMarkerSize(MarkerSize * fs);
    // The legend draws the marker 2.3 pen widths wide: as in the plot.
    plot->SetWidth(MarkerSize * fs / 2.3f);
    plot->SetLabel(seriesNames[s]);
  }

  // The labels and axis titles, over the chart.
  vtkNew<ChartOverlay> overlay;
  overlay->Chart = chart;
  overlay->Scale = fs;
  for (std::size_t i = 0; i < points.size(); ++i)
    overlay->Entries.push_back({ points[i].time, points[i].error, points[i].label, onFront[i] });
  view->GetScene()->AddItem(overlay);

  // Render, read back, average down, write.
  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->ShouldRerenderOff(); // the frame just rendered, not another one
  vtkNew<vtkImageShrink3D> shrink;
  shrink->SetInputConnection(grab->GetOutputPort());
  shrink->SetShrinkFactors(scale, scale, 1);
  shrink->AveragingOn();
  vtkNew<vtkPNGWriter> png;
  png->SetInputConnection(shrink->GetOutputPort());
  png->SetFileName(pngPath.c_str());
  png->Write();
  if (png->GetErrorCode())
  {
    error = "cannot write '" + pngPath + "'";
    return false;
  }
  return true;
}
}
