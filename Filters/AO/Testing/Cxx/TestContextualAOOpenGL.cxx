// The OpenGL backend of the filters on real data (neghip.slc, HeadMRVolume),
// with the exactness suite's poses (random, grazing, touching, camera
// margin, leaving, covering, centred), a CPU and an OpenGL pipeline side by
// side:
//  - GPU CAO equals the GPU full recompute bit for bit (the filter's Verify,
//    on the stored 16-bit values) over every voxel not fully clipped;
//  - the category masks are identical to the CPU's, and so are the clipped
//    opacities (bit for bit);
//  - the AO differs from the CPU's by at most 1e-5. The GPU stores AO as
//    16-bit unorm (q = ao * 65535 + 0.5): one rounding, at most
//    0.5 / 65535 = 7.63e-6. The march runs the CPU's operations in the same
//    order with `precise` (no FMA contraction, no reassociation), so what a
//    GPU's own division or summation rounding adds is ~1e-7; 1e-5 covers both.
//  - the depth maps the OpenGL pipeline rasterised, peeled, dilated and
//    eroded on the GPU are the CPU's, bit for bit (all six arrays);
//  - a dilation at 0.3 of the derived radius makes the GPU verification
//    fail, so this test can fail.
// Exits 125 when there is no OpenGL 4.3 context.
#include "caoFilterTestUtilities.h"
#include "caoGLContext.h"
#include "vtkCAOInput.h"

#include "vtkClipDepthMaps.h"
#include "vtkContextualAmbientOcclusion.h"
#include "vtkFloatArray.h"
#include "vtkLocalAmbientOcclusion.h"
#include "vtkMetaImageReader.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkTransform.h"
#include "vtkUnsignedCharArray.h"

#include "caoTestSkip.h"
#include <algorithm>
#include <cmath>
#include <cstring>

namespace
{
struct Pipeline
{
  vtkNew<vtkLocalAmbientOcclusion> lao;
  vtkNew<vtkClipDepthMaps> maps;
  vtkNew<vtkContextualAmbientOcclusion> cao;
  vtkNew<vtkTransform> pose;
};

void Configure(Pipeline& p, vtkImageData* volume, vtkPolyData* mesh, vtkPiecewiseFunction* tf,
  int pattern, int mode, double dilationScale, int backend)
{
  p.lao->SetInputData(volume);
  p.lao->SetOpacityFunction(tf);
  p.lao->SetQualityToCustom(); // the settings below apply
  p.lao->SetRayPattern(pattern);
  const double* s = volume->GetSpacing();
  p.lao->SetReach(4.0 * std::min({ s[0], s[1], s[2] }));
  p.lao->SetNumberOfSamples(4);
  p.lao->SetBackend(backend);
  p.maps->SetInputData(mesh);
  p.maps->SetReach(p.lao->GetReach());
  p.maps->SetVoxelSpacing(volume->GetSpacing());
  p.maps->SetDilationScale(dilationScale);
  p.maps->SetNumberOfLayers(2);
  p.maps->SetBackend(backend);
  p.cao->SetInputConnection(0, p.lao->GetOutputPort());
  p.cao->SetInputConnection(1, p.maps->GetOutputPort());
  p.cao->SetMode(mode);
  p.cao->SetBackend(backend);
  p.cao->SetVerify(true);
  p.cao->SetPoseTransform(p.pose);
}

struct Outcome
{
  int poses = 0, affectedPoses = 0, differingPoses = 0, cpuDifferingPoses = 0;
  vtkIdType mapPixels = 0; // depth-map pixels compared bit for bit
  double maxGpuCpu = 0.0;
};

int Run(vtkImageData* volume, vtkPolyData* mesh, const std::vector<vtkCAO::Pose>& poses,
  int pattern, int mode, double dilationScale, bool requireExact, Outcome& out)
{
  vtkNew<vtkPiecewiseFunction> tf;
  tf->AddPoint(0, 0);
  tf->AddPoint(30, 0);
  tf->AddPoint(255, 0.9);
  Pipeline cpu, gpu;
  Configure(cpu, volume, mesh, tf, pattern, mode, dilationScale,
    vtkContextualAmbientOcclusion::CPU);
  Configure(gpu, volume, mesh, tf, pattern, mode, dilationScale,
    vtkContextualAmbientOcclusion::OPENGL);
  caotest::EventCounter events;
  events.Watch(gpu.cao);
  events.Watch(gpu.lao);
  events.Watch(cpu.cao);
  for (const auto& p : poses)
  {
    vtkCAO::PoseToTransform(p, cpu.pose);
    vtkCAO::PoseToTransform(p, gpu.pose);
    cpu.maps->SetPoseScaleRange(p.scale, p.scale); // maps made for each pose's scale
    gpu.maps->SetPoseScaleRange(p.scale, p.scale);
    cpu.cao->Update();
    gpu.cao->Update();
    CAO_CHECK(events.errors == 0, "filter error: %s", events.lastError.c_str());
    vtkImageData* c = cpu.cao->GetOutput();
    vtkImageData* g = gpu.cao->GetOutput();
    auto* backend = vtkStringArray::SafeDownCast(g->GetFieldData()->GetAbstractArray("ComputeBackend"));
    CAO_CHECK(backend && backend->GetValue(0).rfind("OpenGL", 0) == 0, "the GPU pipeline ran on %s",
      backend ? backend->GetValue(0).c_str() : "?");
    const double differing = caotest::Field(g, "Verification", 1);
    out.cpuDifferingPoses += caotest::Field(c, "Verification", 1) > 0;
    CAO_CHECK(differing >= 0.0, "no GPU verification record");
    ++out.poses;
    out.differingPoses += differing > 0;
    out.affectedPoses += caotest::Field(g, "CategoryCounts", 1) > 0;
    if (!requireExact)
      continue;
    if (out.poses == 1)
    {
      vtkImageData* cm = cpu.maps->GetOutput();
      vtkImageData* gm = gpu.maps->GetOutput();
      auto* mapsBackend =
        vtkStringArray::SafeDownCast(gm->GetFieldData()->GetAbstractArray("ComputeBackend"));
      CAO_CHECK(mapsBackend && mapsBackend->GetValue(0).rfind("OpenGL", 0) == 0,
        "the GPU depth maps ran on %s", mapsBackend ? mapsBackend->GetValue(0).c_str() : "?");
      for (const char* name : { "FrontDepth", "BackDepth", "DilatedFrontDepth", "DilatedBackDepth",
             "ErodedFrontDepth", "ErodedBackDepth" })
      {
        auto* a = vtkFloatArray::SafeDownCast(cm->GetPointData()->GetArray(name));
        auto* b = vtkFloatArray::SafeDownCast(gm->GetPointData()->GetArray(name));
        CAO_CHECK(a && b && a->GetNumberOfValues() == b->GetNumberOfValues() &&
            std::memcmp(a->GetPointer(0), b->GetPointer(0), a->GetNumberOfValues() * sizeof(float)) == 0,
          "the GPU's %s differs from the CPU's", name);
      }
      out.mapPixels = cm->GetNumberOfPoints();
    }
    auto* cc = vtkUnsignedCharArray::SafeDownCast(c->GetPointData()->GetArray("ClipCategory"));
    auto* gc = vtkUnsignedCharArray::SafeDownCast(g->GetPointData()->GetArray("ClipCategory"));
    auto* co = vtkFloatArray::SafeDownCast(c->GetPointData()->GetArray("ClippedOpacity"));
    auto* go = vtkFloatArray::SafeDownCast(g->GetPointData()->GetArray("ClippedOpacity"));
    auto* ca = vtkFloatArray::SafeDownCast(c->GetPointData()->GetArray("AmbientOcclusion"));
    auto* ga = vtkFloatArray::SafeDownCast(g->GetPointData()->GetArray("AmbientOcclusion"));
    CAO_CHECK(cc && gc && co && go && ca && ga, "missing output arrays");
    std::int64_t maskDiff = 0, opacityDiff = 0;
    double maxDiff = 0.0;
    for (vtkIdType v = 0; v < cc->GetNumberOfTuples(); ++v)
    {
      maskDiff += cc->GetValue(v) != gc->GetValue(v);
      opacityDiff += !(co->GetValue(v) == go->GetValue(v));
      if (cc->GetValue(v) != 0)
        maxDiff = std::max(maxDiff, std::fabs(double(ca->GetValue(v)) - ga->GetValue(v)));
    }
    CAO_CHECK(differing == 0.0, "GPU CAO differs from the GPU full recompute on %g voxels",
      differing);
    CAO_CHECK(maskDiff == 0, "%lld voxels have another category on the GPU", (long long)maskDiff);
    CAO_CHECK(opacityDiff == 0, "%lld voxels have another clipped opacity on the GPU",
      (long long)opacityDiff);
    CAO_CHECK(maxDiff <= 1e-5, "GPU AO differs from CPU AO by %g", maxDiff);
    out.maxGpuCpu = std::max(out.maxGpuCpu, maxDiff);
  }
  return 0;
}
}

int TestContextualAOOpenGL(int argc, char* argv[])
{
  {
    std::string why;
    if (caotest::PretendNoGL() || !cao::gl::Context::CreateHeadless(cao::gl::ContextKind::Auto, why))
      return caotest::NoGL("no OpenGL 4.3 context: " + why);
  }
  const std::string data = caotest::DataDirectory(argc, argv);
  vtkSmartPointer<vtkImageData> neghip = caotest::ReadSLC(data + "/neghip.slc");
  vtkNew<vtkMetaImageReader> head;
  head->SetFileName((data + "/HeadMRVolume.mhd").c_str());
  head->Update();
  CAO_CHECK(neghip->GetNumberOfPoints() == 66 * 66 * 66, "neghip.slc not read");
  struct Shape
  {
    const char* name;
    vtkImageData* volume;
    int pattern, mode;
    double size;
    int poses;
  };
  const Shape shapes[] = {
    { "sphere", neghip, vtkLocalAmbientOcclusion::RAYS_6, vtkContextualAmbientOcclusion::SUBTRACTION, 14.0, 14 },
    { "cube", neghip, vtkLocalAmbientOcclusion::RAYS_6, vtkContextualAmbientOcclusion::SUBTRACTION, 11.0, 14 },
    { "torus", head->GetOutput(), vtkLocalAmbientOcclusion::RAYS_14, vtkContextualAmbientOcclusion::SUBTRACTION, 40.0, 14 },
    { "torus", neghip, vtkLocalAmbientOcclusion::RAYS_26, vtkContextualAmbientOcclusion::PROBING, 20.0, 6 }
  };
  unsigned seed = 11;
  for (const Shape& shape : shapes)
  {
    std::string error;
    auto mesh = vtkCAO::MakeShape(shape.name, shape.size, error);
    CAO_CHECK(mesh, "%s", error.c_str());
    double bounds[6];
    shape.volume->GetBounds(bounds);
    Outcome out;
    if (Run(shape.volume, mesh, caotest::MakePoses(bounds, shape.size, seed++, shape.poses),
          shape.pattern, shape.mode, 1.0, true, out))
      return 1;
    std::printf("%s (%s): GPU depth maps == CPU's (%lld pixels x 2 layers x 6 maps), %d poses, "
                "%d with affected voxels, GPU CAO == GPU full at all, masks identical, "
                "max |GPU - CPU| %.3g\n",
      shape.name, shape.mode == vtkContextualAmbientOcclusion::PROBING ? "probing" : "subtraction",
      static_cast<long long>(out.mapPixels), out.poses, out.affectedPoses, out.maxGpuCpu);
    CAO_CHECK(out.affectedPoses >= shape.poses / 2, "too few poses affect the volume (%d)",
      out.affectedPoses);
  }
  // Negative control: an undersized dilation must be caught on the GPU too.
  {
    std::string error;
    auto mesh = vtkCAO::MakeShape("sphere", 14.0, error);
    double bounds[6];
    neghip->GetBounds(bounds);
    Outcome out;
    if (Run(neghip, mesh, caotest::MakePoses(bounds, 14.0, 5, 20), vtkLocalAmbientOcclusion::RAYS_6,
          vtkContextualAmbientOcclusion::SUBTRACTION, 0.3, false, out))
      return 1;
    std::printf("undersized dilation: %d of %d poses differ on the GPU, %d on the CPU\n",
      out.differingPoses, out.poses, out.cpuDifferingPoses);
    CAO_CHECK(out.differingPoses > 0, "an undersized dilation went unnoticed on the GPU");
  }
  return 0;
}
