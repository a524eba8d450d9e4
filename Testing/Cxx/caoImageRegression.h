/**
 * caoImageRegression — image regression for the tests: capture a VTK render
 * window, write it as PNG, and compare it with a PNG baseline through
 * OpenImageIO (ImageBufAlgo::compare) with a per-pixel threshold and a
 * maximum fraction of failing pixels.
 *
 * Baselines are made by the project's own renderer: with the environment
 * variable CAO_UPDATE_BASELINES=1 a comparison writes the baseline instead
 * (and says so); baselines are checked by eye before they are committed.
 */
#ifndef caoImageRegression_h
#define caoImageRegression_h

#include <string>
#include <vector>

class vtkRenderWindow;

namespace caotest
{
/// An 8-bit RGB image, top row first (as PNG stores it).
struct Image
{
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;
  bool operator==(const Image& o) const
  {
    return width == o.width && height == o.height && rgb == o.rgb;
  }
};

/// Read the window's last rendered frame (the back buffer).
Image Capture(vtkRenderWindow* window);

/// Pixels that differ at all between two images of the same size (-1 if sizes differ).
long DifferingPixels(const Image& a, const Image& b);

bool WritePNG(const Image& image, const std::string& path, std::string& error);

struct Tolerance
{
  /// A pixel fails when any channel differs by more than this (0..1 scale).
  float pixelThreshold = 0.0f;
  /// The comparison fails when more than this fraction of pixels fail.
  double failFraction = 0.0;
};

/**
 * Compare `image` with the PNG baseline `baseline`; the rendered image is
 * also written to `output` for inspection. Prints one line with the
 * result. With CAO_UPDATE_BASELINES=1 it writes the baseline and passes.
 */
bool CompareWithBaseline(const Image& image, const std::string& baseline,
  const std::string& output, const Tolerance& tolerance);
}

#endif
