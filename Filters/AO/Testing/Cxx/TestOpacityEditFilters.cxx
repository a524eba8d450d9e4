// Transfer-function edits through the VTK filters, on HeadMR: the LAO
// filter updates its AO by recomputing only the voxels within the rays'
// reach of a voxel whose opacity changed (caoOpacityEdit), and a clipped
// scene downstream (vtkContextualAmbientOcclusion with two subtracting
// shapes and a probing one) follows, exact at every step:
//  - the LAO equals a fresh full LAO with the same function bit for bit,
//    and says "opacity edit" with the voxels it changed and recomputed;
//  - the contextual AO equals its full recompute (Verify) after each edit,
//    the clip's state kept valid across the edit (a pose moved after an
//    edit, and an edit while carved);
//  - the hard cases: opacity raised from zero, lowered to zero, one scalar
//    bin, the whole range, no change (nothing recomputed);
//  - what forces a full run says so: the ray settings changed, the
//    scalars changed (negative control for the reason field).
#include "caoFilterTestUtilities.h"
#include "vtkCAOInput.h"

#include "vtkClipDepthMaps.h"
#include "vtkContextualAmbientOcclusion.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLocalAmbientOcclusion.h"
#include "vtkMatrix4x4.h"
#include "vtkMetaImageReader.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkTransform.h"

#include <string>
#include <vector>

namespace
{
std::string Reason(vtkDataObject* d)
{
  auto* a = vtkStringArray::SafeDownCast(d->GetFieldData()->GetAbstractArray("LAOUpdate"));
  return a && a->GetNumberOfValues() ? a->GetValue(0) : std::string("(none)");
}

void Set(vtkPiecewiseFunction* tf, const std::vector<double>& points)
{
  tf->RemoveAllPoints();
  for (std::size_t i = 0; i < points.size(); i += 2)
    tf->AddPoint(points[i], points[i + 1]);
}
}

int TestOpacityEditFilters(int argc, char* argv[])
{
  const std::string data = caotest::DataDirectory(argc, argv);
  vtkNew<vtkMetaImageReader> head;
  head->SetFileName((data + "/HeadMRVolume.mhd").c_str());
  head->Update();
  vtkImageData* volume = head->GetOutput();
  CAO_CHECK(volume->GetNumberOfPoints() == 48 * 62 * 42, "HeadMRVolume not read");
  const double voxels = static_cast<double>(volume->GetNumberOfPoints());
  double b[6];
  volume->GetBounds(b);
  const double c[3] = { 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]) };

  vtkNew<vtkPiecewiseFunction> tf;
  const std::vector<double> base = { 0, 0, 40, 0, 191, 0.6, 255, 0 };
  Set(tf, base);
  vtkNew<vtkLocalAmbientOcclusion> lao;
  lao->SetInputData(volume);
  lao->SetOpacityFunction(tf);
  lao->SetQualityToCustom();
  lao->SetRayPattern(vtkLocalAmbientOcclusion::RAYS_14);
  lao->SetReach(12.0);
  lao->SetBackend(vtkAOAlgorithm::CPU);
  // Two subtracting shapes and a probing sphere, in the volume's frame.
  vtkNew<vtkClipDepthMaps> maps;
  maps->SetReach(12.0);
  maps->SetVoxelSpacing(volume->GetSpacing());
  maps->SetNumberOfLayers(8);
  maps->SetBackend(vtkAOAlgorithm::CPU);
  std::string error;
  const char* shapes[3] = { "sphere", "cube", "sphere" };
  const double sizes[3] = { 24, 16, 80 };
  const int modes[3] = { vtkContextualAmbientOcclusion::SUBTRACTION,
    vtkContextualAmbientOcclusion::SUBTRACTION, vtkContextualAmbientOcclusion::PROBING };
  std::vector<vtkSmartPointer<vtkMatrix4x4>> poses;
  for (int i = 0; i < 3; ++i)
  {
    maps->AddInputData(0, vtkCAO::MakeShape(shapes[i], sizes[i], error));
    poses.push_back(vtkSmartPointer<vtkMatrix4x4>::New());
    vtkNew<vtkTransform> t;
    t->Translate(c[0] + (i == 0 ? 20 : i == 1 ? -15 : 0), c[1] + (i == 1 ? 10 : 0), c[2]);
    poses.back()->DeepCopy(t->GetMatrix());
    maps->SetShapePose(i, poses.back());
    maps->SetShapeMode(i, modes[i]);
  }
  vtkNew<vtkContextualAmbientOcclusion> cao;
  cao->SetInputConnection(0, lao->GetOutputPort());
  cao->SetInputConnection(1, maps->GetOutputPort());
  cao->SetBackend(vtkAOAlgorithm::CPU);
  cao->VerifyOn();
  vtkNew<vtkTransform> identity;
  cao->SetPoseTransform(identity);
  caotest::EventCounter events;
  events.Watch(lao);
  events.Watch(cao);
  events.Watch(maps);

  auto fresh = [&](const std::vector<double>& points) {
    vtkNew<vtkPiecewiseFunction> f;
    Set(f, points);
    vtkNew<vtkLocalAmbientOcclusion> full;
    full->SetInputData(volume);
    full->SetOpacityFunction(f);
    full->SetQualityToCustom();
    full->SetRayPattern(vtkLocalAmbientOcclusion::RAYS_14);
    full->SetReach(12.0);
    full->SetBackend(vtkAOAlgorithm::CPU);
    full->Update();
    return vtkSmartPointer<vtkDataArray>(full->GetOutput()->GetPointData()->GetArray("AmbientOcclusion"));
  };
  cao->Update();
  CAO_CHECK(events.errors == 0, "%s", events.lastError.c_str());
  CAO_CHECK(Reason(lao->GetOutput()) == "first run", "first: %s", Reason(lao->GetOutput()).c_str());
  CAO_CHECK(caotest::Field(cao->GetOutput(), "Verification", 0) == 0.0, "first pose not exact");

  struct Edit
  {
    const char* name;
    std::vector<double> to;
    bool all; // every voxel's opacity changes
  };
  const std::vector<Edit> edits = {
    { "raised from zero (the top quarter)", { 0, 0, 40, 0, 191, 0.6, 255, 0.9 }, false },
    { "lowered to zero (back)", base, false },
    { "one scalar bin (20, in the clear range)", { 0, 0, 19, 0, 20, 0.9, 21, 0, 40, 0, 191, 0.6, 255, 0 }, false },
    { "no change", { 0, 0, 19, 0, 20, 0.9, 21, 0, 40, 0, 191, 0.6, 255, 0 }, false },
    { "the whole range", { 0, 0.05, 255, 0.7 }, true },
  };
  int step = 0;
  for (const Edit& e : edits)
  {
    Set(tf, e.to);
    if (step == 2)
    {
      // The clip moves between two edits: the contextual state follows both.
      vtkNew<vtkTransform> t;
      t->Translate(c[0] - 10, c[1] - 5, c[2] + 6);
      poses[0]->DeepCopy(t->GetMatrix());
    }
    cao->Update();
    ++step;
    CAO_CHECK(events.errors == 0, "%s: %s", e.name, events.lastError.c_str());
    vtkImageData* out = lao->GetOutput();
    const double changed = caotest::Field(out, "LAOUpdateVoxels", 0);
    const double recomputed = caotest::Field(out, "LAOUpdateVoxels", 1);
    const bool same = caotest::SameBits(out->GetPointData()->GetArray("AmbientOcclusion"), fresh(e.to));
    const double verification = caotest::Field(cao->GetOutput(), "Verification", 0);
    std::printf("%-36s %s: %7.0f changed, %7.0f recomputed of %.0f; equals a full LAO: %s; "
                "contextual AO against its full recompute: %g\n",
      e.name, Reason(out).c_str(), changed, recomputed, voxels, same ? "yes" : "NO", verification);
    CAO_CHECK(Reason(out) == "opacity edit", "%s: %s", e.name, Reason(out).c_str());
    CAO_CHECK(same, "%s: the edited LAO differs from a full LAO", e.name);
    CAO_CHECK(verification == 0.0, "%s: the contextual AO differs from its full recompute", e.name);
    if (std::string(e.name) == "no change")
      CAO_CHECK(changed == 0 && recomputed == 0, "no change recomputed %g", recomputed);
    else if (!e.all)
      CAO_CHECK(changed > 0 && recomputed < voxels, "%s: %g of %g recomputed", e.name, recomputed, voxels);
    else
      CAO_CHECK(changed == voxels, "%s: %g changed", e.name, changed);
  }
  // The last AO is edited in place when nothing else holds it (no new
  // pages, no copy), never when something does: an array an earlier output
  // handed out keeps its values.
  {
    vtkSmartPointer<vtkDataArray> held = lao->GetOutput()->GetPointData()->GetArray("AmbientOcclusion");
    vtkNew<vtkFloatArray> before;
    before->DeepCopy(held);
    const std::vector<double> to = { 0, 0, 40, 0, 150, 0.5, 255, 0.8 };
    Set(tf, to);
    lao->Update();
    vtkDataArray* now = lao->GetOutput()->GetPointData()->GetArray("AmbientOcclusion");
    CAO_CHECK(Reason(lao->GetOutput()) == "opacity edit" && now != held.Get() &&
        caotest::SameBits(held, before) && caotest::SameBits(now, fresh(to)),
      "a held AO array changed, or the edit beside it is not exact");
    void* address = now->GetVoidPointer(0);
    held = nullptr;
    const std::vector<double> again = { 0, 0, 40, 0, 120, 0.4, 255, 0.9 };
    Set(tf, again);
    lao->Update();
    now = lao->GetOutput()->GetPointData()->GetArray("AmbientOcclusion");
    CAO_CHECK(Reason(lao->GetOutput()) == "opacity edit" && now->GetVoidPointer(0) == address &&
        caotest::SameBits(now, fresh(again)),
      "an AO array nobody holds was not edited in place, or the edit is not exact");
    // Without the kept buffers the next edit allocates them again, exact.
    lao->ReleaseEditBuffers();
    double cached[2]; // (a range asked for caches it in the array)
    lao->GetOutput()->GetPointData()->GetArray("AmbientOcclusion")->GetRange(cached);
    Set(tf, to);
    lao->Update();
    CAO_CHECK(Reason(lao->GetOutput()) == "opacity edit" &&
        caotest::SameBits(lao->GetOutput()->GetPointData()->GetArray("AmbientOcclusion"), fresh(to)),
      "the edit after ReleaseEditBuffers is not exact");
    // The range of the array written in place is the new one, not the one
    // cached before the edit.
    double range[2];
    lao->GetOutput()->GetPointData()->GetArray("AmbientOcclusion")->GetRange(range);
    double want[2];
    fresh(to)->GetRange(want);
    CAO_CHECK(range[0] == want[0] && range[1] == want[1],
      "the edited AO's range is stale: [%g, %g], a full run's [%g, %g]", range[0], range[1], want[0], want[1]);
    std::printf("a held AO array keeps its values; one nobody holds is edited in place, exact\n");
  }
  // The opacity likewise, on a filter nothing downstream holds: an edit
  // writes the new opacity over the last one (the changed voxels' mask
  // alongside, no second array) when nothing else holds it; a held one
  // keeps its values; either way the AO and the opacity are a full run's.
  {
    vtkNew<vtkPiecewiseFunction> f;
    vtkNew<vtkLocalAmbientOcclusion> solo;
    solo->SetInputData(volume);
    solo->SetOpacityFunction(f);
    solo->SetQualityToCustom();
    solo->SetRayPattern(vtkLocalAmbientOcclusion::RAYS_14);
    solo->SetReach(12.0);
    solo->SetBackend(vtkAOAlgorithm::CPU);
    const auto full = [&](const std::vector<double>& points) {
      vtkNew<vtkPiecewiseFunction> g;
      Set(g, points);
      vtkNew<vtkLocalAmbientOcclusion> run;
      run->SetInputData(volume);
      run->SetOpacityFunction(g);
      run->SetQualityToCustom();
      run->SetRayPattern(vtkLocalAmbientOcclusion::RAYS_14);
      run->SetReach(12.0);
      run->SetBackend(vtkAOAlgorithm::CPU);
      run->Update();
      vtkSmartPointer<vtkImageData> out = vtkSmartPointer<vtkImageData>::New();
      out->ShallowCopy(run->GetOutput());
      return out;
    };
    const auto opacityOf = [](vtkImageData* d) { return d->GetPointData()->GetArray("AmbientOcclusionOpacity"); };
    const auto aoOf = [](vtkImageData* d) { return d->GetPointData()->GetArray("AmbientOcclusion"); };
    Set(f, base);
    solo->Update();
    vtkSmartPointer<vtkDataArray> held = opacityOf(solo->GetOutput());
    vtkNew<vtkFloatArray> before;
    before->DeepCopy(held);
    const std::vector<double> to = { 0, 0, 40, 0, 191, 0.6, 255, 0.9 };
    Set(f, to);
    solo->Update();
    auto want = full(to);
    vtkDataArray* now = opacityOf(solo->GetOutput());
    CAO_CHECK(Reason(solo->GetOutput()) == "opacity edit" && now != held.Get() && caotest::SameBits(held, before) &&
        caotest::SameBits(now, opacityOf(want)) && caotest::SameBits(aoOf(solo->GetOutput()), aoOf(want)),
      "a held opacity array changed, or the edit beside it is not a full run's");
    void* address = now->GetVoidPointer(0);
    held = nullptr;
    const std::vector<double> again = { 0, 0, 40, 0, 120, 0.4, 255, 0.9 };
    Set(f, again);
    solo->Update();
    want = full(again);
    now = opacityOf(solo->GetOutput());
    CAO_CHECK(Reason(solo->GetOutput()) == "opacity edit" && now->GetVoidPointer(0) == address &&
        caotest::SameBits(now, opacityOf(want)) && caotest::SameBits(aoOf(solo->GetOutput()), aoOf(want)),
      "an opacity array nobody holds was not written over in place, or the edit is not a full run's");
    std::printf("a held opacity array keeps its values; one nobody holds is written over in place, exact\n");
  }
  // What forces a full run says why (and the result is still exact).
  lao->SetReach(10.0);
  maps->SetReach(10.0);
  cao->Update();
  CAO_CHECK(Reason(lao->GetOutput()) == "the ray settings changed", "reach: %s",
    Reason(lao->GetOutput()).c_str());
  CAO_CHECK(caotest::Field(lao->GetOutput(), "LAOUpdateVoxels", 1) == voxels, "not a full run");
  CAO_CHECK(caotest::Field(cao->GetOutput(), "Verification", 0) == 0.0, "not exact after reach");
  vtkNew<vtkImageData> copy;
  copy->DeepCopy(volume);
  lao->SetInputData(copy);
  lao->Update();
  CAO_CHECK(Reason(lao->GetOutput()) == "the scalars changed", "scalars: %s",
    Reason(lao->GetOutput()).c_str());
  std::printf("full runs: \"the ray settings changed\", \"the scalars changed\"\nPASSED\n");
  return 0;
}
