// Several clip shapes at once, each with its own pose and mode
// (vtkClipDepthMaps with several inputs, caoClipComposite), on HeadMR:
//  - 8 subtracting shapes (spheres, cubes, tori, posed and rotated), moved
//    one at a time over 5 poses; 2 probing spheres less a subtracting
//    cube over 3 poses;
//  - at every pose the contextual AO equals its full recompute (Verify, CPU),
//    and the clip agrees with the exact combination of the exact shapes
//    (ClipShape::Composite; vtkCAO::CheckClipGeometry: no voxel inside by
//    more than one map pixel plus the tessellation left, none outside
//    touched);
//  - on OpenGL (when a 4.3 context exists) the same poses give the same
//    categories and clipped opacities, and AO within 1e-5 of the CPU's;
//  - negative control: the check against the combination without one of
//    the shapes finds wrong voxels;
//  - bad input: 33 shapes, an unknown mode, a pose without a mesh are
//    refused with the limit.
#include "caoFilterTestUtilities.h"
#include "vtkCAOClipMaps.h"
#include "vtkCAOInput.h"

#include "caoClipComposite.h"
#include "caoGLContext.h"
#include "vtkClipDepthMaps.h"
#include "vtkContextualAmbientOcclusion.h"
#include "vtkFloatArray.h"
#include "vtkLocalAmbientOcclusion.h"
#include "vtkMatrix4x4.h"
#include "vtkMetaImageReader.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkTransform.h"
#include "vtkUnsignedCharArray.h"

#include <cmath>
#include <random>

namespace
{
struct Part
{
  std::string shape;
  double size;
  int mode;
  vtkCAO::Pose pose;
};

struct Pipeline
{
  vtkNew<vtkLocalAmbientOcclusion> lao;
  vtkNew<vtkClipDepthMaps> maps;
  vtkNew<vtkContextualAmbientOcclusion> cao;
  std::vector<vtkSmartPointer<vtkMatrix4x4>> poses;
  std::vector<vtkSmartPointer<vtkPolyData>> meshes;
};

void Build(Pipeline& p, vtkImageData* volume, vtkPiecewiseFunction* tf, double reach,
  const std::vector<Part>& parts, int backend)
{
  p.lao->SetInputData(volume);
  p.lao->SetOpacityFunction(tf);
  p.lao->SetQualityToCustom(); // the settings below apply
  p.lao->SetRayPattern(vtkLocalAmbientOcclusion::RAYS_6);
  p.lao->SetReach(reach);
  p.lao->SetNumberOfSamples(4);
  p.lao->SetBackend(backend);
  p.maps->SetReach(reach);
  p.maps->SetVoxelSpacing(volume->GetSpacing());
  p.maps->SetNumberOfLayers(8);
  p.maps->SetBackend(backend);
  std::string error;
  for (std::size_t i = 0; i < parts.size(); ++i)
  {
    p.meshes.push_back(vtkCAO::MakeShape(parts[i].shape, parts[i].size, error));
    p.maps->AddInputData(0, p.meshes.back());
    p.poses.push_back(vtkSmartPointer<vtkMatrix4x4>::New());
    p.maps->SetShapePose(static_cast<int>(i), p.poses.back());
    p.maps->SetShapeMode(static_cast<int>(i), parts[i].mode);
  }
  p.cao->SetInputConnection(0, p.lao->GetOutputPort());
  p.cao->SetInputConnection(1, p.maps->GetOutputPort());
  p.cao->SetBackend(backend);
  p.cao->VerifyOn();
  vtkNew<vtkTransform> identity; // the maps live in the volume's frame
  p.cao->SetPoseTransform(identity);
}

void Pose(Pipeline& p, const std::vector<Part>& parts)
{
  for (std::size_t i = 0; i < parts.size(); ++i)
  {
    vtkNew<vtkTransform> t;
    vtkCAO::PoseToTransform(parts[i].pose, t);
    p.poses[i]->DeepCopy(t->GetMatrix()); // modifies the matrix: new maps
  }
}

/// The exact combination, leaving out part `skip` (-1: none).
cao::ClipShape Exact(const std::vector<Part>& parts, int skip, double& deviation)
{
  std::vector<cao::ClipShapePart> exact;
  deviation = 0.0;
  std::string error;
  for (std::size_t i = 0; i < parts.size(); ++i)
  {
    if (static_cast<int>(i) == skip)
      continue;
    cao::ClipShapePart e;
    const double s = parts[i].size;
    e.shape = parts[i].shape == "sphere" ? cao::ClipShape::Sphere(s)
      : parts[i].shape == "cube"         ? cao::ClipShape::Cube(s)
                                         : cao::ClipShape::Torus(s, s / 3.0);
    std::vector<double> pts;
    std::vector<std::int64_t> tris;
    vtkCAO::TrianglesOf(vtkCAO::MakeShape(parts[i].shape, s, error), pts, tris);
    deviation = std::max(deviation, e.shape.Deviation(cao::ViewMesh(pts, tris)));
    vtkNew<vtkTransform> t;
    vtkCAO::PoseToTransform(parts[i].pose, t);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c)
        e.localToCommon[4 * r + c] = t->GetMatrix()->GetElement(r, c);
    e.mode = parts[i].mode;
    exact.push_back(std::move(e));
  }
  return cao::ClipShape::Composite(std::move(exact));
}
}

int TestSeveralClipShapes(int argc, char* argv[])
{
  const std::string data = caotest::DataDirectory(argc, argv);
  vtkNew<vtkMetaImageReader> head;
  head->SetFileName((data + "/HeadMRVolume.mhd").c_str());
  head->Update();
  vtkImageData* volume = head->GetOutput();
  CAO_CHECK(volume->GetNumberOfPoints() == 48 * 62 * 42, "HeadMRVolume not read");
  double bounds[6];
  volume->GetBounds(bounds);
  vtkNew<vtkPiecewiseFunction> tf;
  tf->AddPoint(0, 0);
  tf->AddPoint(40, 0);
  tf->AddPoint(255, 0.9);
  const double reach = 16.0;
  std::string why;
  const bool gl = cao::gl::Context::CreateHeadless(cao::gl::ContextKind::Auto, why) != nullptr;
  if (!gl)
    std::printf("note: no OpenGL 4.3 context (%s): the CPU half only\n", why.c_str());

  std::mt19937 rng(2611);
  auto inside = [&](int axis) {
    std::uniform_real_distribution<double> u(0.15, 0.85);
    return bounds[2 * axis] + u(rng) * (bounds[2 * axis + 1] - bounds[2 * axis]);
  };
  auto angle = [&]() { return std::uniform_real_distribution<double>(-180, 180)(rng); };
  auto place = [&](Part& part) {
    for (int d = 0; d < 3; ++d)
    {
      part.pose.translation[d] = inside(d);
      part.pose.rotation[d] = angle();
    }
  };
  const int S = vtkContextualAmbientOcclusion::SUBTRACTION, P = vtkContextualAmbientOcclusion::PROBING;
  std::vector<Part> eight = { { "sphere", 22, S, {} }, { "cube", 16, S, {} }, { "torus", 24, S, {} },
    { "sphere", 14, S, {} }, { "cube", 12, S, {} }, { "sphere", 30, S, {} }, { "torus", 18, S, {} },
    { "cube", 20, S, {} } };
  std::vector<Part> lens = { { "sphere", 70, P, {} }, { "sphere", 70, P, {} }, { "cube", 18, S, {} } };
  struct Scene
  {
    const char* name;
    std::vector<Part>* parts;
    int poses;
  } scenes[] = { { "8 subtractions", &eight, 5 }, { "2 probes less a cube", &lens, 3 } };
  int checked = 0;
  for (Scene& scene : scenes)
  {
    for (Part& part : *scene.parts)
      place(part);
    if (scene.parts == &lens) // two overlapping probes around the centre
      for (int d = 0; d < 3; ++d)
      {
        const double c = 0.5 * (bounds[2 * d] + bounds[2 * d + 1]);
        lens[0].pose.translation[d] = c + (d == 0 ? -25 : 0);
        lens[1].pose.translation[d] = c + (d == 0 ? 25 : 0);
        lens[2].pose.translation[d] = c;
      }
    Pipeline cpu, gpu;
    Build(cpu, volume, tf, reach, *scene.parts, vtkAOAlgorithm::CPU);
    if (gl)
      Build(gpu, volume, tf, reach, *scene.parts, vtkAOAlgorithm::OPENGL);
    caotest::EventCounter events;
    events.Watch(cpu.lao);
    events.Watch(cpu.maps);
    events.Watch(cpu.cao);
    for (int k = 0; k < scene.poses; ++k)
    {
      if (k > 0) // move one shape
      {
        Part& moved = (*scene.parts)[k % scene.parts->size()];
        for (int d = 0; d < 3; ++d)
          moved.pose.translation[d] += 0.1 * (bounds[2 * d + 1] - bounds[2 * d]);
        moved.pose.rotation[1] += 35.0;
      }
      Pose(cpu, *scene.parts);
      cpu.cao->Update();
      CAO_CHECK(events.errors == 0 && events.warnings == 0, "%s pose %d: %s", scene.name, k,
        events.lastError.c_str());
      vtkImageData* out = cpu.cao->GetOutput();
      CAO_CHECK(caotest::Field(out, "Verification", 0) == 0.0,
        "%s pose %d: CAO differs from the full recompute", scene.name, k);
      CAO_CHECK(caotest::Field(cpu.maps->GetOutput(), "DepthMapStatistics", 1) == 0.0,
        "%s pose %d: more intervals than the 8 layers", scene.name, k);
      vtkCAO::ClipMaps held;
      std::string error;
      CAO_CHECK(vtkCAO::ReadClipMaps(cpu.maps->GetOutput(), cao::layout::CAO_MODE_SUBTRACT, held,
                  error) && held.composite,
        "%s", error.c_str());
      double deviation = 0.0;
      const cao::ClipShape exact = Exact(*scene.parts, -1, deviation);
      vtkNew<vtkMatrix4x4> identity;
      cao::ClipGeometryReport report;
      CAO_CHECK(vtkCAO::CheckClipGeometry(out, held, identity, exact, deviation, held.mode, report,
                  error),
        "%s", error.c_str());
      const double a = caotest::Field(out, "CategoryCounts", 0);
      const double b = caotest::Field(out, "CategoryCounts", 1);
      std::printf("%-22s pose %d: mode %d, clipped %g, affected %g; inside %lld, outside %lld "
                  "checked, wrong %lld + %lld (margin %.3g)\n",
        scene.name, k, held.mode, a, b, (long long)report.mustBeInside,
        (long long)report.mustBeOutside, (long long)report.wrongInside,
        (long long)report.wrongOutside, report.margin);
      CAO_CHECK(report.Passed() && report.mustBeInside > 500 && report.mustBeOutside > 10000,
        "%s pose %d: the clip disagrees with the exact shapes (%s)", scene.name, k,
        report.firstWrong.c_str());
      if (k == 0)
      {
        // Negative control: without one shape the combination is not what
        // was clipped.
        const int skip = scene.parts == &lens ? 2 : 5;
        const cao::ClipShape fewer = Exact(*scene.parts, skip, deviation);
        cao::ClipGeometryReport wrong;
        vtkCAO::CheckClipGeometry(out, held, identity, fewer, deviation, held.mode, wrong, error);
        std::printf("  negative control (shape %d left out): %lld + %lld wrong\n", skip,
          (long long)wrong.wrongInside, (long long)wrong.wrongOutside);
        CAO_CHECK(!wrong.Passed(), "%s: leaving shape %d out went unnoticed", scene.name, skip);
      }
      if (gl)
      {
        Pose(gpu, *scene.parts);
        gpu.cao->Update();
        vtkImageData* g = gpu.cao->GetOutput();
        CAO_CHECK(caotest::Field(g, "Verification", 0) == 0.0,
          "%s pose %d: GPU CAO differs from its full recompute", scene.name, k);
        auto* ca = vtkFloatArray::SafeDownCast(out->GetPointData()->GetArray("AmbientOcclusion"));
        auto* ga = vtkFloatArray::SafeDownCast(g->GetPointData()->GetArray("AmbientOcclusion"));
        auto* cc = out->GetPointData()->GetArray("ClipCategory");
        auto* gc = g->GetPointData()->GetArray("ClipCategory");
        CAO_CHECK(ca && ga && cc && gc, "arrays missing");
        double maxDiff = 0.0;
        long long categories = 0;
        for (vtkIdType v = 0; v < ca->GetNumberOfTuples(); ++v)
        {
          maxDiff = std::max(maxDiff, std::fabs(double(ca->GetValue(v)) - ga->GetValue(v)));
          categories += cc->GetTuple1(v) != gc->GetTuple1(v);
        }
        CAO_CHECK(categories == 0 && maxDiff <= 1e-5,
          "%s pose %d: GPU and CPU differ (%lld categories, AO by %g)", scene.name, k, categories,
          maxDiff);
      }
      ++checked;
    }
  }

  // Bad input.
  {
    std::string error;
    vtkNew<vtkClipDepthMaps> maps;
    caotest::EventCounter refused;
    refused.Watch(maps);
    for (int i = 0; i < 33; ++i)
      maps->AddInputData(0, vtkCAO::MakeShape("sphere", 5.0, error));
    maps->SetShapeMode(0, 1);
    maps->SetBackendToCPU();
    maps->Update();
    CAO_CHECK(refused.errors > 0 && refused.lastError.find("at most 32") != std::string::npos,
      "33 shapes: '%s'", refused.lastError.c_str());
    vtkNew<vtkClipDepthMaps> one;
    refused.Watch(one);
    one->SetShapeMode(0, 5);
    CAO_CHECK(refused.lastError.find("0 (subtraction) or 1 (probing)") != std::string::npos,
      "mode 5: '%s'", refused.lastError.c_str());
    one->AddInputData(0, vtkCAO::MakeShape("sphere", 5.0, error));
    vtkNew<vtkMatrix4x4> m;
    one->SetShapePose(1, m);
    one->SetBackendToCPU();
    one->Update();
    CAO_CHECK(refused.lastError.find("no pose or mode without a mesh") != std::string::npos,
      "pose without a mesh: '%s'", refused.lastError.c_str());
  }
  std::printf("%d poses of several clip shapes: exact against the full recompute and the exact "
              "shapes%s; negative controls caught\n",
    checked, gl ? ", GPU equal to CPU" : "");
  return 0;
}
