#include "caoImageRegression.h"

#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkRenderWindow.h"
#include "vtkUnsignedCharArray.h"
#include "vtkPointData.h"
#include "vtkWindowToImageFilter.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace caotest
{
Image Capture(vtkRenderWindow* window)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->ShouldRerenderOff();
  grab->Update();
  vtkImageData* data = grab->GetOutput();
  int dims[3];
  data->GetDimensions(dims);
  Image image;
  image.width = dims[0];
  image.height = dims[1];
  image.rgb.resize(static_cast<std::size_t>(3) * dims[0] * dims[1]);
  auto* pixels = vtkUnsignedCharArray::SafeDownCast(data->GetPointData()->GetScalars());
  const unsigned char* src = pixels->GetPointer(0);
  const std::size_t row = static_cast<std::size_t>(3) * dims[0];
  for (int y = 0; y < dims[1]; ++y) // VTK's rows run bottom-up
    std::memcpy(&image.rgb[row * y], src + row * (dims[1] - 1 - y), row);
  return image;
}

long DifferingPixels(const Image& a, const Image& b)
{
  if (a.width != b.width || a.height != b.height)
    return -1;
  long n = 0;
  for (std::size_t p = 0; p + 2 < a.rgb.size(); p += 3)
    n += (a.rgb[p] != b.rgb[p] || a.rgb[p + 1] != b.rgb[p + 1] || a.rgb[p + 2] != b.rgb[p + 2]);
  return n;
}

namespace
{
OIIO::ImageBuf ToBuffer(const Image& image)
{
  OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::UINT8);
  OIIO::ImageBuf buf(spec);
  buf.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::UINT8, image.rgb.data());
  return buf;
}
}

bool WritePNG(const Image& image, const std::string& path, std::string& error)
{
  OIIO::ImageBuf buf = ToBuffer(image);
  if (!buf.write(path))
  {
    error = buf.geterror();
    return false;
  }
  return true;
}

bool CompareWithBaseline(const Image& image, const std::string& baseline,
  const std::string& output, const Tolerance& tolerance)
{
  std::string error;
  if (!WritePNG(image, output, error))
  {
    std::printf("FAIL: cannot write %s: %s\n", output.c_str(), error.c_str());
    return false;
  }
  const char* update = std::getenv("CAO_UPDATE_BASELINES");
  if (update && std::strcmp(update, "1") == 0)
  {
    const bool ok = WritePNG(image, baseline, error);
    std::printf("%s baseline %s\n", ok ? "wrote" : "FAILED to write", baseline.c_str());
    return ok;
  }
  OIIO::ImageBuf reference(baseline);
  if (!reference.read(0, 0, true, OIIO::TypeDesc::UINT8))
  {
    std::printf("FAIL: cannot read the baseline %s: %s\n", baseline.c_str(),
      reference.geterror().c_str());
    return false;
  }
  const OIIO::ImageSpec& spec = reference.spec();
  if (spec.width != image.width || spec.height != image.height || spec.nchannels < 3)
  {
    std::printf("FAIL: %s is %dx%dx%d, the render %dx%dx3\n", baseline.c_str(), spec.width,
      spec.height, spec.nchannels, image.width, image.height);
    return false;
  }
  OIIO::ImageBuf rendered = ToBuffer(image);
  OIIO::ImageBuf rgb = OIIO::ImageBufAlgo::channels(reference, 3, {});
  const auto result = OIIO::ImageBufAlgo::compare(
    rendered, rgb, tolerance.pixelThreshold, tolerance.pixelThreshold);
  const double pixels = static_cast<double>(image.width) * image.height;
  const double fraction = static_cast<double>(result.nfail) / pixels;
  // CompareResults::error is also raised when some pixel exceeds the
  // threshold; the verdict here is the fraction of such pixels.
  const bool ok = fraction <= tolerance.failFraction;
  std::printf("%s: %s vs %s: %lld pixel(s) over %.4f (%.4f%%, allowed %.4f%%), max error %.4f, "
              "mean %.6f\n",
    ok ? "ok" : "FAIL", output.c_str(), baseline.c_str(), static_cast<long long>(result.nfail),
    tolerance.pixelThreshold, 100.0 * fraction, 100.0 * tolerance.failFraction, result.maxerror,
    result.meanerror);
  return ok;
}
}
