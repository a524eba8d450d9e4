// Numerically hard cases: each asserts an exact value or a stated bound.
#include "caoFilterTestUtilities.h"
#include "vtkCAOInput.h"

#include "vtkClipDepthMaps.h"
#include "vtkContextualAmbientOcclusion.h"
#include "vtkFloatArray.h"
#include "vtkLocalAmbientOcclusion.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPolyData.h"
#include "vtkTransform.h"
#include "vtkUnsignedCharArray.h"

#include <cmath>
#include <limits>

namespace
{
vtkSmartPointer<vtkImageData> Constant(int nx, int ny, int nz, double value, const double spacing[3])
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(nx, ny, nz);
  image->SetSpacing(spacing[0], spacing[1], spacing[2]);
  image->AllocateScalars(VTK_FLOAT, 1);
  auto* s = vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars());
  s->FillValue(static_cast<float>(value));
  return image;
}

/// LAO output array of `image` with an identity transfer function on [0,1],
/// with the paper's march (start offset 0) for which the closed forms below
/// are derived, unless `offset` says otherwise.
vtkSmartPointer<vtkFloatArray> LAO(vtkImageData* image, int pattern, double reach, int samples,
  caotest::EventCounter* events = nullptr, double offset = 0.0)
{
  vtkNew<vtkPiecewiseFunction> tf;
  tf->AddPoint(0.0, 0.0);
  tf->AddPoint(1.0, 1.0);
  vtkNew<vtkLocalAmbientOcclusion> lao;
  if (events)
    events->Watch(lao);
  lao->SetQualityToCustom(); // the cases state their settings
  lao->SetRayVariationToNone();
  lao->SetStartOffset(offset);
  lao->SetInputData(image);
  lao->SetOpacityFunction(tf);
  lao->SetRayPattern(pattern);
  lao->SetReach(reach);
  lao->SetNumberOfSamples(samples);
  lao->Update();
  return vtkFloatArray::SafeDownCast(lao->GetOutput()->GetPointData()->GetArray("AmbientOcclusion"));
}

float At(vtkFloatArray* a, vtkImageData* image, int i, int j, int k)
{
  int d[3];
  image->GetDimensions(d);
  return a->GetValue(i + d[0] * (j + static_cast<vtkIdType>(d[1]) * k));
}
}

int TestAmbientOcclusionHardCases(int argc, char* argv[])
{
  const double unit[3] = { 1, 1, 1 };
  const int R6 = vtkLocalAmbientOcclusion::RAYS_6, R26 = vtkLocalAmbientOcclusion::RAYS_26;

  // All transparent: every ray sums M transmittances of 1: exactly 1.
  {
    auto image = Constant(12, 9, 7, 0.0, unit);
    auto ao = LAO(image, R26, 3.0, 3);
    for (vtkIdType i = 0; i < ao->GetNumberOfValues(); ++i)
      CAO_CHECK(ao->GetValue(i) == 1.0f, "transparent: %.9g", ao->GetValue(i));
  }
  // All opaque: an interior voxel's first sample is opaque on every ray,
  // so each ray sums exactly 1: AO = K / (K*M) = 1/M exactly.
  {
    auto image = Constant(9, 9, 9, 1.0, unit);
    auto ao = LAO(image, R26, 2.0, 2);
    CAO_CHECK(At(ao, image, 4, 4, 4) == 26.0f / 52.0f, "opaque centre: %.9g", At(ao, image, 4, 4, 4));
    for (vtkIdType i = 0; i < ao->GetNumberOfValues(); ++i)
      CAO_CHECK(ao->GetValue(i) >= 0.5f && ao->GetValue(i) <= 1.0f, "opaque range");
  }
  // A single voxel: the axis rays sample whole voxels away, whose cells lie
  // entirely outside, so AO = 1 exactly; diagonal rays' first samples still
  // reach the voxel itself through the trilinear footprint, so with 26 rays
  // the value is below 1 but finite and positive.
  {
    auto image = Constant(1, 1, 1, 1.0, unit);
    auto ao = LAO(image, R6, 5.0, 5);
    CAO_CHECK(ao->GetValue(0) == 1.0f, "single voxel, 6 rays: %.9g", ao->GetValue(0));
    // Mid-step samples (offset 0.5, the default): the first sample of each
    // axis ray, half a voxel out, sees opacity 1/2; the rest see nothing:
    // each ray sums 1 + 4 * 1/2 = 3, AO = 18 / 30 exactly as rounded.
    ao = LAO(image, R6, 5.0, 5, nullptr, 0.5);
    CAO_CHECK(ao->GetValue(0) == 0.6f, "single voxel, 6 rays, offset 0.5: %.9g", ao->GetValue(0));
    ao = LAO(image, R26, 5.0, 5);
    CAO_CHECK(ao->GetValue(0) > 0.5f && ao->GetValue(0) < 1.0f, "single voxel, 26 rays: %.9g",
      ao->GetValue(0));
  }
  // One voxel thick, opaque: the 2 out-of-plane rays see nothing (sum M),
  // the 4 in-plane rays stop at their first sample (sum 1):
  // AO = (2M + 4) / (6M) = 12/24 for M = 4.
  {
    auto image = Constant(16, 16, 1, 1.0, unit);
    auto ao = LAO(image, R6, 4.0, 4);
    CAO_CHECK(At(ao, image, 8, 8, 0) == 12.0f / 24.0f, "slab: %.9g", At(ao, image, 8, 8, 0));
  }
  // Anisotropic spacing 1:1:100: z rays sample between two opaque slices,
  // the lerp of equal values is exact, so the centre is exactly 1/M.
  {
    const double aniso[3] = { 1, 1, 100 };
    auto image = Constant(7, 7, 7, 1.0, aniso);
    auto ao = LAO(image, R6, 3.0, 3);
    CAO_CHECK(At(ao, image, 3, 3, 3) == 6.0f / 18.0f, "anisotropic: %.9g", At(ao, image, 3, 3, 3));
  }
  // A reach smaller than one voxel: samples inside the voxel's cells.
  {
    auto image = Constant(5, 5, 5, 1.0, unit);
    auto ao = LAO(image, R26, 0.3, 3);
    CAO_CHECK(At(ao, image, 2, 2, 2) == 26.0f / 78.0f, "short reach: %.9g", At(ao, image, 2, 2, 2));
    image->GetPointData()->GetScalars()->SetComponent(62, 0, 0.25);
    // The default M is at least 2 (round(0.3) would give 1 sample, whose
    // transmittance is 1 before anything occludes it: AO = 1 everywhere):
    // the opaque neighbours occlude.
    ao = LAO(image, R26, 0.3, 0);
    CAO_CHECK(At(ao, image, 2, 2, 2) > 0.5f && At(ao, image, 2, 2, 2) < 1.0f,
      "M = 2 by default for R < 1.5 voxels: %.9g", At(ao, image, 2, 2, 2));
  }
  // A reach far larger than the volume: rays leave it after a few samples;
  // values stay finite in [0, 1] and CAO stays exact (every voxel affected).
  {
    const std::string data = caotest::DataDirectory(argc, argv);
    vtkSmartPointer<vtkImageData> neghip = caotest::ReadSLC(data + "/neghip.slc");
    vtkNew<vtkPiecewiseFunction> tf;
    tf->AddPoint(0, 0);
    tf->AddPoint(255, 0.5);
    vtkNew<vtkLocalAmbientOcclusion> lao;
    lao->SetInputData(neghip);
    lao->SetOpacityFunction(tf);
    lao->SetQualityToCustom();
    lao->SetRayVariationToNone();
    lao->SetRayPattern(R6);
    lao->SetReach(1000.0);
    lao->SetNumberOfSamples(16);
    std::string error;
    auto mesh = vtkCAO::MakeShape("sphere", 10.0, error);
    vtkNew<vtkClipDepthMaps> maps;
    maps->SetInputData(mesh);
    maps->SetReach(1000.0);
    vtkNew<vtkContextualAmbientOcclusion> cao;
    cao->SetInputConnection(0, lao->GetOutputPort());
    cao->SetInputConnection(1, maps->GetOutputPort());
    vtkNew<vtkTransform> pose;
    pose->Translate(33, 33, 33);
    cao->SetPoseTransform(pose);
    cao->VerifyOn();
    cao->Update();
    auto* ao = vtkFloatArray::SafeDownCast(cao->GetOutput()->GetPointData()->GetArray("AmbientOcclusion"));
    CAO_CHECK(ao, "no AO for a huge reach");
    for (vtkIdType i = 0; i < ao->GetNumberOfValues(); ++i)
      CAO_CHECK(std::isfinite(ao->GetValue(i)) && ao->GetValue(i) >= 0 && ao->GetValue(i) <= 1,
        "huge reach: %.9g", ao->GetValue(i));
    CAO_CHECK(caotest::Field(cao->GetOutput(), "Verification", 0) == 0.0, "huge reach: CAO not exact");
    CAO_CHECK(caotest::Field(cao->GetOutput(), "CategoryCounts", 2) == 0.0,
      "huge reach: every unclipped voxel is affected");
  }
  // M = 1: the sum would have one term, the empty product: 1 everywhere,
  // whatever the volume. Refused with an error (one), and no AO array.
  {
    auto image = Constant(6, 6, 6, 0.7, unit);
    caotest::EventCounter events;
    auto ao = LAO(image, R26, 4.0, 1, &events);
    CAO_CHECK(!ao && events.errors >= 1 && events.lastError.find("one sees no occluder") != std::string::npos,
      "M = 1 must be refused with the reason (AO array %s, %d error(s): %s)", ao ? "made" : "none",
      events.errors, events.lastError.c_str());
  }
  // NaN and Inf scalars: transparent, one warning; the result equals that of
  // the same volume with 0 (transparent) there, bit for bit.
  {
    auto image = Constant(10, 10, 10, 0.6, unit);
    auto clean = Constant(10, 10, 10, 0.6, unit);
    auto* s = image->GetPointData()->GetScalars();
    const vtkIdType bad[] = { 0, 111, 555, 999 };
    const double values[] = { std::numeric_limits<double>::quiet_NaN(),
      std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
      std::numeric_limits<double>::quiet_NaN() };
    for (int i = 0; i < 4; ++i)
    {
      s->SetComponent(bad[i], 0, values[i]);
      clean->GetPointData()->GetScalars()->SetComponent(bad[i], 0, 0.0);
    }
    caotest::EventCounter events;
    auto ao = LAO(image, R26, 3.0, 3, &events);
    CAO_CHECK(events.warnings == 1 && events.errors == 0, "NaN/Inf: %d warnings, %d errors",
      events.warnings, events.errors);
    auto reference = LAO(clean, R26, 3.0, 3);
    CAO_CHECK(caotest::SameBits(ao, reference), "NaN/Inf voxels must act as transparent");
  }
  // Transfer-function opacities of exactly 0 and 1 survive the step
  // correction exactly, for any unit distance.
  {
    vtkSmartPointer<vtkImageData> neghip =
      caotest::ReadSLC(caotest::DataDirectory(argc, argv) + "/neghip.slc");
    vtkNew<vtkPiecewiseFunction> tf;
    tf->AddPoint(0, 0);
    tf->AddPoint(100, 0);
    tf->AddPoint(100.5, 1);
    tf->AddPoint(255, 1);
    vtkNew<vtkLocalAmbientOcclusion> lao;
    lao->SetInputData(neghip);
    lao->SetOpacityFunction(tf);
    lao->SetScalarOpacityUnitDistance(0.37);
    lao->SetRayPattern(R6);
    lao->Update();
    auto* op = vtkFloatArray::SafeDownCast(
      lao->GetOutput()->GetPointData()->GetArray("AmbientOcclusionOpacity"));
    auto* scalars = neghip->GetPointData()->GetScalars();
    int zeros = 0, ones = 0;
    for (vtkIdType i = 0; i < op->GetNumberOfValues(); ++i)
    {
      const double v = scalars->GetComponent(i, 0);
      const float expected = v <= 100 ? 0.0f : 1.0f;
      CAO_CHECK(op->GetValue(i) == expected, "opacity %.9g for scalar %g", op->GetValue(i), v);
      zeros += expected == 0.0f;
      ones += expected == 1.0f;
    }
    CAO_CHECK(zeros > 0 && ones > 0, "both plateaus must occur");
  }
  // An origin at 1e6: LAO is translation invariant, bit for bit, and CAO
  // with the mesh moved by the same 1e6 gives the same mask and AO.
  {
    vtkSmartPointer<vtkImageData> near =
      caotest::ReadSLC(caotest::DataDirectory(argc, argv) + "/neghip.slc");
    auto far = vtkSmartPointer<vtkImageData>::New();
    far->ShallowCopy(near);
    far->SetOrigin(1e6, 1e6, 1e6);
    std::string error;
    auto mesh = vtkCAO::MakeShape("cube", 12.0, error);
    vtkSmartPointer<vtkImageData> out[2];
    for (int run = 0; run < 2; ++run)
    {
      vtkNew<vtkPiecewiseFunction> tf;
      tf->AddPoint(0, 0);
      tf->AddPoint(255, 0.8);
      vtkNew<vtkLocalAmbientOcclusion> lao;
      lao->SetInputData(run ? far : near);
      lao->SetOpacityFunction(tf);
      lao->SetRayPattern(R6);
      vtkNew<vtkClipDepthMaps> maps;
      maps->SetInputData(mesh);
      vtkNew<vtkContextualAmbientOcclusion> cao;
      cao->SetInputConnection(0, lao->GetOutputPort());
      cao->SetInputConnection(1, maps->GetOutputPort());
      vtkNew<vtkTransform> pose;
      const double shift = run ? 1e6 : 0.0;
      pose->Translate(30.25 + shift, 31.5 + shift, 29.75 + shift);
      pose->RotateZ(30);
      cao->SetPoseTransform(pose);
      cao->VerifyOn();
      cao->Update();
      CAO_CHECK(caotest::Field(cao->GetOutput(), "Verification", 0) == 0.0, "origin 1e6: not exact");
      out[run] = vtkSmartPointer<vtkImageData>::New();
      out[run]->ShallowCopy(cao->GetOutput());
    }
    CAO_CHECK(caotest::Field(out[0], "CategoryCounts", 1) > 0, "the cube must affect voxels");
    CAO_CHECK(caotest::SameBits(out[0]->GetPointData()->GetArray("ClipCategory"),
                out[1]->GetPointData()->GetArray("ClipCategory")),
      "origin 1e6 changes the category mask");
    CAO_CHECK(caotest::SameBits(out[0]->GetPointData()->GetArray("AmbientOcclusion"),
                out[1]->GetPointData()->GetArray("AmbientOcclusion")),
      "origin 1e6 changes the AO");
  }
  return 0;
}
