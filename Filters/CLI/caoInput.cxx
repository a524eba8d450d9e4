#include "caoInput.h"

#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkCleanPolyData.h"
#include "vtkCommand.h"
#include "vtkCubeSource.h"
#include "vtkDataArray.h"
#include "vtkDataSetReader.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkMetaImageReader.h"
#include "vtkNIFTIImageReader.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkPLYReader.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSLCReader.h"
#include "vtkSTLReader.h"
#include "vtkSphereSource.h"
#include "vtkTransform.h"
#include "vtkTriangleFilter.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLPolyDataReader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace caocli
{
namespace
{
std::string Lower(std::string s)
{
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

bool EndsWith(const std::string& s, const std::string& tail)
{
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

/// Runs a reader with its errors captured instead of printed.
struct ErrorCatcher
{
  std::string message;
  vtkNew<vtkCallbackCommand> callback;
  explicit ErrorCatcher(vtkAlgorithm* algorithm)
  {
    callback->SetClientData(this);
    callback->SetCallback([](vtkObject*, unsigned long, void* self, void* data) {
      auto* catcher = static_cast<ErrorCatcher*>(self);
      if (catcher->message.empty() && data)
        catcher->message = static_cast<const char*>(data);
    });
    algorithm->AddObserver(vtkCommand::ErrorEvent, callback);
    if (auto* exec = algorithm->GetExecutive())
      exec->AddObserver(vtkCommand::ErrorEvent, callback);
  }
};

bool Readable(const std::string& path, std::string& error)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    error = "cannot open '" + path + "'";
    return false;
  }
  return true;
}

template <typename Reader>
bool Run(Reader* reader, const std::string& path, std::string& error)
{
  ErrorCatcher catcher(reader);
  reader->Update();
  if (!catcher.message.empty())
  {
    std::string m = catcher.message;
    while (!m.empty() && std::isspace(static_cast<unsigned char>(m.back())))
      m.pop_back();
    error = "cannot read '" + path + "': " + m;
    return false;
  }
  return true;
}
}

std::vector<std::string> Split(const std::string& s, char sep)
{
  std::vector<std::string> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, sep))
    if (!item.empty())
      out.push_back(item);
  return out;
}

bool ToDouble(const std::string& s, double& v)
{
  char* end = nullptr;
  v = std::strtod(s.c_str(), &end);
  return !s.empty() && *end == '\0' && std::isfinite(v);
}

double FieldValue(vtkDataObject* d, const char* name, int component, double missing)
{
  vtkDataArray* a = d ? d->GetFieldData()->GetArray(name) : nullptr;
  return a && a->GetNumberOfTuples() > 0 && component >= 0 &&
      component < a->GetNumberOfComponents()
    ? a->GetComponent(0, component)
    : missing;
}

void DefaultOpacityRamp(const double range[2], vtkPiecewiseFunction* tf)
{
  const double lo = range[0], hi = range[1] > range[0] ? range[1] : range[0] + 1.0;
  tf->AddPoint(lo, 0.0);
  tf->AddPoint(lo + 0.25 * (hi - lo), 0.0);
  tf->AddPoint(hi, 0.8);
}

vtkSmartPointer<vtkImageData> ReadVolume(const std::string& path, std::string& error)
{
  if (!Readable(path, error))
    return nullptr;
  const std::string p = Lower(path);
  vtkSmartPointer<vtkImageData> image;
  if (EndsWith(p, ".vti"))
  {
    vtkNew<vtkXMLImageDataReader> r;
    r->SetFileName(path.c_str());
    if (!Run(r.Get(), path, error))
      return nullptr;
    image = r->GetOutput();
  }
  else if (EndsWith(p, ".mhd") || EndsWith(p, ".mha"))
  {
    vtkNew<vtkMetaImageReader> r;
    r->SetFileName(path.c_str());
    if (!r->CanReadFile(path.c_str()))
    {
      error = "cannot read '" + path + "': not a MetaImage file";
      return nullptr;
    }
    if (!Run(r.Get(), path, error))
      return nullptr;
    image = r->GetOutput();
  }
  else if (EndsWith(p, ".slc"))
  {
    vtkNew<vtkSLCReader> r;
    r->SetFileName(path.c_str());
    if (!r->CanReadFile(path.c_str()))
    {
      error = "cannot read '" + path + "': not an SLC file";
      return nullptr;
    }
    if (!Run(r.Get(), path, error))
      return nullptr;
    image = r->GetOutput();
  }
  else if (EndsWith(p, ".nii") || EndsWith(p, ".nii.gz"))
  {
    vtkNew<vtkNIFTIImageReader> r;
    r->SetFileName(path.c_str());
    if (!r->CanReadFile(path.c_str()))
    {
      error = "cannot read '" + path + "': not a NIfTI file";
      return nullptr;
    }
    if (!Run(r.Get(), path, error))
      return nullptr;
    image = r->GetOutput();
  }
  else if (EndsWith(p, ".vtk"))
  {
    vtkNew<vtkDataSetReader> r;
    r->SetFileName(path.c_str());
    if (!Run(r.Get(), path, error))
      return nullptr;
    image = vtkImageData::SafeDownCast(r->GetOutput());
    if (!image)
    {
      error = "cannot read '" + path + "': not a structured-points (image) dataset";
      return nullptr;
    }
  }
  else
  {
    error = "unknown volume format '" + path +
      "' (expected .vti, .mhd, .mha, .slc, .vtk, .nii or .nii.gz)";
    return nullptr;
  }
  if (!image || image->GetNumberOfPoints() < 1)
  {
    error = "cannot read '" + path + "': no voxels";
    return nullptr;
  }
  auto copy = vtkSmartPointer<vtkImageData>::New();
  copy->ShallowCopy(image);
  return copy;
}

vtkSmartPointer<vtkPolyData> ReadMesh(const std::string& path, std::string& error)
{
  if (!Readable(path, error))
    return nullptr;
  const std::string p = Lower(path);
  vtkSmartPointer<vtkAlgorithm> reader;
  if (EndsWith(p, ".vtp"))
  {
    auto r = vtkSmartPointer<vtkXMLPolyDataReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else if (EndsWith(p, ".stl"))
  {
    auto r = vtkSmartPointer<vtkSTLReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else if (EndsWith(p, ".ply"))
  {
    auto r = vtkSmartPointer<vtkPLYReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else if (EndsWith(p, ".obj"))
  {
    auto r = vtkSmartPointer<vtkOBJReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else
  {
    error = "unknown mesh format '" + path + "' (expected .vtp, .stl, .ply or .obj)";
    return nullptr;
  }
  if (!Run(reader.Get(), path, error))
    return nullptr;
  auto* mesh = vtkPolyData::SafeDownCast(reader->GetOutputDataObject(0));
  if (!mesh || mesh->GetNumberOfPoints() < 1)
  {
    error = "cannot read '" + path + "': no geometry";
    return nullptr;
  }
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->ShallowCopy(mesh);
  return copy;
}

vtkSmartPointer<vtkPolyData> MakeShape(const std::string& name, double size, std::string& error)
{
  if (!(size > 0.0) || !std::isfinite(size))
  {
    error = "the shape size must be positive";
    return nullptr;
  }
  auto out = vtkSmartPointer<vtkPolyData>::New();
  if (name == "sphere")
  {
    vtkNew<vtkSphereSource> s;
    s->SetRadius(size);
    s->SetThetaResolution(48);
    s->SetPhiResolution(48);
    s->Update();
    out->ShallowCopy(s->GetOutput());
  }
  else if (name == "cube")
  {
    vtkNew<vtkCubeSource> c;
    c->SetXLength(2 * size);
    c->SetYLength(2 * size);
    c->SetZLength(2 * size);
    vtkNew<vtkCleanPolyData> clean; // the source duplicates corners per face
    clean->SetInputConnection(c->GetOutputPort());
    vtkNew<vtkTriangleFilter> tri;
    tri->SetInputConnection(clean->GetOutputPort());
    tri->Update();
    out->ShallowCopy(tri->GetOutput());
  }
  else if (name == "torus")
  {
    // A closed, consistently oriented torus in the xy plane.
    const int nu = 64, nv = 24;
    const double R = size, r = size / 3.0, twoPi = 6.283185307179586;
    vtkNew<vtkPoints> points;
    vtkNew<vtkCellArray> polys;
    for (int i = 0; i < nu; ++i)
    {
      const double u = twoPi * i / nu;
      for (int j = 0; j < nv; ++j)
      {
        const double v = twoPi * j / nv;
        points->InsertNextPoint((R + r * std::cos(v)) * std::cos(u),
          (R + r * std::cos(v)) * std::sin(u), r * std::sin(v));
      }
    }
    for (int i = 0; i < nu; ++i)
    {
      for (int j = 0; j < nv; ++j)
      {
        const vtkIdType a = i * nv + j, b = ((i + 1) % nu) * nv + j,
                        c = ((i + 1) % nu) * nv + (j + 1) % nv, d = i * nv + (j + 1) % nv;
        const vtkIdType t1[3] = { a, b, c }, t2[3] = { a, c, d };
        polys->InsertNextCell(3, t1);
        polys->InsertNextCell(3, t2);
      }
    }
    out->SetPoints(points);
    out->SetPolys(polys);
  }
  else
  {
    error = "unknown shape '" + name + "' (expected sphere, cube or torus)";
    return nullptr;
  }
  return out;
}

bool ParsePose(const std::string& text, Pose& pose, std::string& error)
{
  std::string t = text;
  std::replace(t.begin(), t.end(), ',', ' ');
  std::istringstream in(t);
  std::vector<double> v;
  std::string word;
  while (in >> word)
  {
    char* end = nullptr;
    const double x = std::strtod(word.c_str(), &end);
    if (*end != '\0' || !std::isfinite(x))
    {
      error = "bad number '" + word + "' in pose '" + text + "'";
      return false;
    }
    v.push_back(x);
  }
  if (v.size() != 3 && v.size() != 6 && v.size() != 7)
  {
    error = "a pose is 'tx ty tz [rx ry rz [scale]]', got '" + text + "'";
    return false;
  }
  pose = Pose{};
  for (int i = 0; i < 3; ++i)
    pose.translation[i] = v[i];
  if (v.size() >= 6)
    for (int i = 0; i < 3; ++i)
      pose.rotation[i] = v[3 + i];
  if (v.size() == 7)
  {
    if (!(v[6] > 0.0))
    {
      error = "the pose scale must be positive in '" + text + "'";
      return false;
    }
    pose.scale = v[6];
  }
  return true;
}

bool ReadPoses(const std::string& path, std::vector<Pose>& poses, std::string& error)
{
  std::ifstream in(path);
  if (!in)
  {
    error = "cannot open pose file '" + path + "'";
    return false;
  }
  std::string line;
  int number = 0;
  while (std::getline(in, line))
  {
    ++number;
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#')
      continue;
    Pose p;
    if (!ParsePose(line, p, error))
    {
      error = path + ":" + std::to_string(number) + ": " + error;
      return false;
    }
    poses.push_back(p);
  }
  if (poses.empty())
  {
    error = "pose file '" + path + "' has no poses";
    return false;
  }
  return true;
}

void PoseToTransform(const Pose& p, vtkTransform* t)
{
  t->Identity();
  t->PostMultiply();
  t->Scale(p.scale, p.scale, p.scale);
  t->RotateY(p.rotation[1]);
  t->RotateX(p.rotation[0]);
  t->RotateZ(p.rotation[2]);
  t->Translate(p.translation.data());
}

std::vector<Pose> DefaultPath(const double b[6], int count)
{
  std::vector<Pose> poses;
  const double c[3] = { 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]) };
  const double e[3] = { b[1] - b[0], b[3] - b[2], b[5] - b[4] };
  for (int i = 0; i < count; ++i)
  {
    // From 0.7 of the half-diagonal outside one corner to outside the other.
    const double t = count > 1 ? -0.75 + 1.5 * i / (count - 1) : 0.0;
    Pose p;
    p.translation = { c[0] + t * e[0], c[1] + 0.8 * t * e[1], c[2] + 0.6 * t * e[2] };
    p.rotation = { 7.0 * i, 11.0 * i, 3.0 * i };
    poses.push_back(p);
  }
  return poses;
}

bool TakeArgument(const std::string& a, std::string& volume, std::string& error)
{
  if (!a.empty() && a[0] == '-')
  {
    error = "unknown option '" + a + "'";
    return false;
  }
  if (!volume.empty())
  {
    error = "unexpected argument '" + a + "'";
    return false;
  }
  volume = a;
  return true;
}
}
