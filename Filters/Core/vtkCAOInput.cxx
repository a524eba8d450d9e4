#include "vtkCAOInput.h"

#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCleanPolyData.h"
#include "vtkCommand.h"
#include "vtkCubeSource.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "caoFileChecks.h"

#include <sys/stat.h>

#include "vtkDataSetReader.h"
#include "vtkExecutive.h"
#include "vtkImageData.h"
#include "vtkMatrix4x4.h"
#include "vtkMetaImageReader.h"
#include "vtkNIFTIImageReader.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"
#include "vtkSmartPointer.h"
#include "vtkPLYReader.h"
#include "vtkPointData.h"
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
#include <cstdio>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <utility>
#include <vector>

namespace vtkCAO
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
    // Readers report some read failures as warnings ("Error reading binary
    // data!"); those are errors here.
    warning->SetClientData(this);
    warning->SetCallback([](vtkObject*, unsigned long, void* self, void* data) {
      auto* catcher = static_cast<ErrorCatcher*>(self);
      const char* text = static_cast<const char*>(data);
      if (catcher->message.empty() && text &&
        (std::strstr(text, "Error") || std::strstr(text, "error") || std::strstr(text, "truncat")))
        catcher->message = text;
    });
    algorithm->AddObserver(vtkCommand::WarningEvent, warning);
  }
  vtkNew<vtkCallbackCommand> warning;
};

std::string Trim(const std::string& s)
{
  const auto b = s.find_first_not_of(" \t\r\n");
  const auto e = s.find_last_not_of(" \t\r\n");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

/// The voxel limit of the kernels (2^31 - 1), stated in errors.
constexpr double MaxVolumeVoxels = static_cast<double>(cao::MaxVoxels);

bool Readable(const std::string& path, std::string& error)
{
  // Before any VTK reader, whose messages for these ("Error parsing XML in
  // stream at line 1") name neither the file nor the reason.
  struct stat info;
  if (::stat(path.c_str(), &info) != 0)
  {
    error = "cannot open '" + path + "': no such file";
    return false;
  }
  if (S_ISDIR(info.st_mode))
  {
    error = "cannot read '" + path + "': it is a directory";
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    error = "cannot open '" + path + "': permission denied or not a regular file";
    return false;
  }
  if (S_ISREG(info.st_mode) && info.st_size == 0)
  {
    error = "cannot read '" + path + "': the file is empty (0 bytes)";
    return false;
  }
  return true;
}

/// VTK's output window replaced while it lives by one that keeps the error
/// and warning texts instead of printing them (restored after).
class CaptureWindow : public vtkOutputWindow
{
public:
  static CaptureWindow* New();
  vtkTypeMacro(CaptureWindow, vtkOutputWindow);
  void DisplayErrorText(const char* text) override { this->Keep(text); }
  // Warnings fail the read only when they report an error (as the
  // reader's own observer takes them: "Error reading binary data!").
  void DisplayWarningText(const char* text) override { this->KeepIfError(text); }
  void DisplayGenericWarningText(const char* text) override { this->KeepIfError(text); }
  void DisplayText(const char*) override {}
  void DisplayDebugText(const char*) override {}
  std::string first;

private:
  void Keep(const char* text)
  {
    if (this->first.empty() && text)
      this->first = text;
  }
  void KeepIfError(const char* text)
  {
    if (text && (std::strstr(text, "Error") || std::strstr(text, "error") ||
                  std::strstr(text, "truncat")))
      this->Keep(text);
  }
};
vtkStandardNewMacro(CaptureWindow);

struct OutputCapture
{
  vtkSmartPointer<vtkOutputWindow> previous = vtkOutputWindow::GetInstance();
  vtkNew<CaptureWindow> window;
  // (vtkErrorMacro also logs through vtkLogger, whatever the window: the
  // cao tool turns vtkLogger's stderr off for its whole run; a library
  // caller keeps its own logging.)
  OutputCapture() { vtkOutputWindow::SetInstance(window); }
  ~OutputCapture() { vtkOutputWindow::SetInstance(previous); }
  std::string FirstError() const { return window->first; }
};

/// A VTK message as one line: without its "ERROR: In FILE, line N" and
/// "vtkClass (0x...): " prefixes, its lines joined.
std::string OneLine(std::string m)
{
  if (m.rfind("ERROR: In ", 0) == 0 || m.rfind("Warning: In ", 0) == 0)
  {
    const auto eol = m.find('\n');
    m = eol == std::string::npos ? std::string() : m.substr(eol + 1);
  }
  const auto object = m.find("): ");
  if (m.rfind("vtk", 0) == 0 && object != std::string::npos && object < 80)
    m = m.substr(object + 3);
  // Control characters (a reader quotes the damaged bytes it met) and
  // bytes outside ASCII would break the line or the terminal: '?'.
  for (char& c : m)
  {
    const unsigned char u = static_cast<unsigned char>(c);
    if (c == '\n' || c == '\r' || c == '\t')
      c = ' ';
    else if (u < 0x20 || u >= 0x7f)
      c = '?';
  }
  m = Trim(m);
  if (m.size() > 300)
    m = m.substr(0, 300) + "...";
  return m.empty() ? std::string("the reader failed") : m;
}

template <typename Reader>
bool Run(Reader* reader, const std::string& path, std::string& error)
{
  // Readers run readers of their own (vtkDataSetReader a
  // vtkStructuredPointsReader) whose errors reach no observer of ours:
  // VTK's output window is swapped for one that keeps them while reading.
  OutputCapture capture;
  ErrorCatcher catcher(reader);
  reader->Update();
  const std::string first = !catcher.message.empty() ? catcher.message : capture.FirstError();
  if (!first.empty())
  {
    error = "cannot read '" + path + "': " + OneLine(first);
    // VTK's words for a body shorter than its header promises.
    if (first.find("Error reading") != std::string::npos || first.find("Premature EOF") != std::string::npos ||
      first.find("Unable to read") != std::string::npos)
      error += " (the file ends before the data its header announces: a truncated copy?)";
    return false;
  }
  return true;
}
}

void CellsAsVoxels(vtkImageData* input, vtkImageData* out)
{
  int extent[6];
  input->GetExtent(extent);
  for (int d = 0; d < 3; ++d)
    extent[2 * d + 1] = std::max(extent[2 * d], extent[2 * d + 1] - 1);
  // Index (i, j, k) of the cells' image is the centre of the cell whose
  // lowest point is (i, j, k): index (1/2, 1/2, 1/2) of the input's.
  double centre[3];
  const double half[3] = { 0.5, 0.5, 0.5 };
  input->TransformContinuousIndexToPhysicalPoint(half, centre);
  out->Initialize();
  out->SetExtent(extent);
  out->SetSpacing(input->GetSpacing());
  out->SetDirectionMatrix(input->GetDirectionMatrix());
  out->SetOrigin(centre);
  out->GetPointData()->ShallowCopy(input->GetCellData());
}

vtkSmartPointer<vtkImageData> ReadVolume(const std::string& path, std::string& error)
{
  if (!Readable(path, error) || !cao::CheckFileByExtension(path, error))
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
    if (!cao::CheckMetaImageFile(path, error))
      return nullptr;
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
  if (static_cast<double>(image->GetNumberOfPoints()) > MaxVolumeVoxels)
  {
    error = "cannot read '" + path + "': " + std::to_string(image->GetNumberOfPoints()) +
      " voxels, above the limit of 2^31-1 (2147483647)";
    return nullptr;
  }
  auto copy = vtkSmartPointer<vtkImageData>::New();
  copy->ShallowCopy(image);
  return copy;
}

vtkSmartPointer<vtkPolyData> ReadMesh(const std::string& path, std::string& error)
{
  if (!Readable(path, error) || !cao::CheckFileByExtension(path, error))
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
  else if (EndsWith(p, ".vtk"))
  {
    auto r = vtkSmartPointer<vtkDataSetReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else
  {
    error = "unknown mesh format '" + path + "' (expected .vtp, .vtk, .stl, .ply or .obj)";
    return nullptr;
  }
  if (!Run(reader.Get(), path, error))
  {
    // VTK's XML reader words an empty mesh (a vtkPolyData with no points,
    // as VTK itself writes one) as a damaged file.
    if (error.find("No Points element") != std::string::npos)
      error = "'" + path + "' holds no points: an empty mesh, nothing to draw or clip";
    return nullptr;
  }
  vtkDataObject* read = reader->GetOutputDataObject(0);
  if (read && !vtkPolyData::SafeDownCast(read))
  {
    error = "'" + path + "' holds a " + read->GetClassName() +
      ", not a polygonal mesh (extract its surface or contour it first)";
    return nullptr;
  }
  auto* mesh = vtkPolyData::SafeDownCast(read);
  if (!mesh || mesh->GetNumberOfPoints() < 1)
  {
    error = "'" + path + "' holds no points: an empty mesh, nothing to draw or clip";
    return nullptr;
  }
  // Cells that name points the file does not hold (readers take the ids as
  // written; every filter after would read out of bounds).
  const vtkIdType points = mesh->GetNumberOfPoints();
  vtkCellArray* cells[4] = { mesh->GetVerts(), mesh->GetLines(), mesh->GetPolys(),
    mesh->GetStrips() };
  for (vtkCellArray* c : cells)
  {
    if (!c)
      continue;
    // Offsets that run backwards or past the connectivity (a damaged
    // OFFSETS block of a legacy 5.1 file) make cells read anywhere.
    if (!c->IsValid())
    {
      error = "cannot read '" + path + "': its cell offsets are not increasing from 0 to the " +
        "number of point ids (the file is damaged)";
      return nullptr;
    }
    if (c->GetNumberOfConnectivityIds() == 0)
      continue;
    double range[2];
    c->GetConnectivityArray()->GetRange(range, 0);
    if (range[0] < 0.0 || range[1] >= static_cast<double>(points))
    {
      error = "cannot read '" + path + "': its cells name point " +
        std::to_string(static_cast<long long>(range[0] < 0.0 ? range[0] : range[1])) +
        " but it holds points 0 to " + std::to_string(static_cast<long long>(points - 1));
      return nullptr;
    }
  }
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->ShallowCopy(mesh);
  return copy;
}

double DefaultShapeSize(vtkImageData* volume)
{
  int dims[3];
  volume->GetDimensions(dims);
  const double* spacing = volume->GetSpacing();
  double smallest = HUGE_VAL;
  for (int d = 0; d < 3; ++d)
    smallest = std::min(smallest, dims[d] * std::fabs(spacing[d]));
  // A quarter of the smallest extent, however small the spacing (a floor
  // in absolute units made every voxel of a volume of spacing 1e-9 clipped).
  return smallest > 0.0 && std::isfinite(smallest) ? 0.25 * smallest : 1.0;
}

namespace
{
/// The largest length of a corner of the volume's bounds mapped by `toShape`.
template <typename ToShape>
double FarthestCorner(vtkImageData* volume, ToShape toShape)
{
  double b[6];
  volume->GetBounds(b);
  double far2 = 0.0;
  for (int c = 0; c < 8; ++c)
  {
    double x[3];
    for (int d = 0; d < 3; ++d)
    {
      x[d] = b[2 * d + ((c >> d) & 1)];
    }
    double l[3];
    toShape(x, l);
    far2 = std::max(far2, l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
  }
  return std::sqrt(far2);
}
}

double PlaneSlabSize(vtkImageData* volume, const std::vector<Pose>& poses)
{
  double size = 1e-6;
  for (const Pose& p : poses)
  {
    // The distance is rotation-invariant: translate and scale only.
    size = std::max(size, 1.25 * FarthestCorner(volume, [&p](const double x[3], double l[3]) {
      for (int d = 0; d < 3; ++d)
      {
        l[d] = (x[d] - p.translation[d]) / p.scale;
      }
    }));
  }
  return size;
}

double PlaneSlabSize(vtkImageData* volume, const double shapeToWorld[16])
{
  const double det = vtkMatrix4x4::Determinant(shapeToWorld);
  if (!(std::abs(det) > 0.0) || !std::isfinite(det))
  {
    return 0.0;
  }
  double inverse[16];
  vtkMatrix4x4::Invert(shapeToWorld, inverse);
  return std::max(1e-6, 1.25 * FarthestCorner(volume, [&inverse](const double x[3], double l[3]) {
    for (int r = 0; r < 3; ++r)
    {
      l[r] = inverse[4 * r] * x[0] + inverse[4 * r + 1] * x[1] + inverse[4 * r + 2] * x[2] +
        inverse[4 * r + 3];
    }
  }));
}

vtkSmartPointer<vtkPolyData> MakeShape(const std::string& name, double size, std::string& error)
{
  if (!(size > 0.0) || !std::isfinite(size))
  {
    error = "the shape size must be positive";
    return nullptr;
  }
  // VTK's shape sources, and the depth maps made from them, hold float32
  // coordinates: a shape sized from a volume 1e38 world units across or
  // more would have infinite points.
  if (size > 1e36)
  {
    std::ostringstream why;
    why << "the " << name << " would reach " << size << " world units from its centre, beyond the float32 "
        << "coordinates of VTK's shape sources and of the clip's depth maps (at most 1e36); scale "
           "the volume's spacing down, or draw it without a clip";
    error = why.str();
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
  else if (name == "plane")
  {
    // The half-space z >= 0 of the pose's frame, as the closed slab
    // [-size, size]^2 x [0, size]: exact wherever the slab covers the volume.
    vtkNew<vtkCubeSource> c;
    c->SetBounds(-size, size, -size, size, 0.0, size);
    vtkNew<vtkCleanPolyData> clean;
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
    error = "unknown shape '" + name + "' (expected sphere, cube, torus or plane)";
    return nullptr;
  }
  return out;
}

bool ParsePose(const std::string& text, Pose& pose, std::string& error)
{
  const std::string trimmed = Trim(text);
  if (!trimmed.empty() && (trimmed.front() == ',' || trimmed.back() == ',' ||
                            trimmed.find(",,") != std::string::npos))
  {
    error = "an empty item in pose '" + text + "'";
    return false;
  }
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
    if (poses.size() > static_cast<std::size_t>(MaxPoses))
    {
      error = "pose file '" + path + "' has more than " + std::to_string(MaxPoses) + " poses";
      return false;
    }
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

void IndexFromZeroToPhysical(vtkImageData* image, vtkMatrix4x4* out)
{
  int extent[6];
  image->GetExtent(extent);
  vtkNew<vtkMatrix4x4> shift;
  shift->SetElement(0, 3, extent[0]);
  shift->SetElement(1, 3, extent[2]);
  shift->SetElement(2, 3, extent[4]);
  vtkMatrix4x4::Multiply4x4(image->GetIndexToPhysicalMatrix(), shift, out);
}

void TrianglesOf(vtkPolyData* mesh, std::vector<double>& points, std::vector<std::int64_t>& tris)
{
  // A mesh of triangles only (no strips, every polygon three points) is
  // read as it is: the triangle filter would copy it whole.
  vtkCellArray* given = mesh->GetPolys();
  if (mesh->GetNumberOfStrips() == 0 && given && given->IsHomogeneous() == 3)
  {
    const vtkIdType count = mesh->GetNumberOfPoints();
    points.resize(3 * static_cast<std::size_t>(count));
    for (vtkIdType i = 0; i < count; ++i)
      mesh->GetPoint(i, &points[3 * i]);
    const vtkIdType cells = given->GetNumberOfCells();
    tris.resize(3 * static_cast<std::size_t>(cells));
    vtkIdType n;
    const vtkIdType* ids;
    for (vtkIdType c = 0; c < cells; ++c) // (by id: the caller's traversal state stays as it was)
    {
      given->GetCellAtId(c, n, ids);
      for (int k = 0; k < 3; ++k)
        tris[3 * static_cast<std::size_t>(c) + k] = ids[k];
    }
    return;
  }
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputData(mesh);
  triangles->PassVertsOff();
  triangles->PassLinesOff();
  triangles->Update();
  vtkPolyData* t = triangles->GetOutput();
  points.resize(3 * static_cast<std::size_t>(t->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < t->GetNumberOfPoints(); ++i)
    t->GetPoint(i, &points[3 * i]);
  tris.clear();
  vtkCellArray* polys = t->GetPolys();
  tris.reserve(3 * static_cast<std::size_t>(polys->GetNumberOfCells()));
  vtkIdType n;
  const vtkIdType* ids;
  for (polys->InitTraversal(); polys->GetNextCell(n, ids);)
    if (n == 3)
      tris.insert(tris.end(), { ids[0], ids[1], ids[2] });
}

bool CheckPoseDistances(const std::vector<Pose>& poses, vtkImageData* volume, std::string& error)
{
  if (!volume)
    return true;
  double b[6], spacing[3];
  volume->GetBounds(b);
  volume->GetSpacing(spacing);
  const double voxel = std::min({ std::fabs(spacing[0]), std::fabs(spacing[1]), std::fabs(spacing[2]) });
  if (!(voxel > 0.0) || !std::isfinite(voxel))
    return true; // (the volume's own checks report it)
  const double limit = 0.5 * MaxClipVoxels * voxel;
  for (std::size_t i = 0; i < poses.size(); ++i)
  {
    double out[3];
    for (int k = 0; k < 3; ++k)
    {
      const double x = poses[i].translation[k];
      out[k] = x < b[2 * k] ? b[2 * k] - x : x > b[2 * k + 1] ? x - b[2 * k + 1] : 0.0;
    }
    const double d = std::hypot(std::hypot(out[0], out[1]), out[2]); // (no overflow at 1e300)
    if (d <= limit)
      continue;
    char text[400];
    std::snprintf(text, sizeof text,
      "pose %zu: the clip shape's centre lies %g world units (%g voxels) from the volume; beyond "
      "2^22 voxels (%g world units here) the depth maps' float32 coordinates cannot place a voxel, "
      "and a shape that far clips nothing: move it nearer or leave the clip out",
      i, d, d / voxel, limit);
    error = text;
    return false;
  }
  return true;
}

bool CheckPoseScales(const std::vector<Pose>& poses, vtkPolyData* mesh, vtkImageData* volume,
  std::string& error, bool largestOnly, double* scales)
{
  if (!mesh || !volume || mesh->GetNumberOfPoints() == 0)
    return true; // the mesh's own checks report it
  double b[6], spacing[3];
  mesh->GetBounds(b);
  volume->GetSpacing(spacing);
  const double size = std::max({ b[1] - b[0], b[3] - b[2], b[5] - b[4] });
  const double voxel = std::min({ std::fabs(spacing[0]), std::fabs(spacing[1]),
    std::fabs(spacing[2]) });
  if (!(size > 0.0) || !std::isfinite(size) || !(voxel > 0.0))
    return true;
  const double lo = 0.5 * voxel / size, hi = MaxClipVoxels * voxel / size;
  if (scales)
  {
    scales[0] = lo;
    scales[1] = hi;
  }
  for (std::size_t i = 0; i < poses.size(); ++i)
  {
    const double s = poses[i].scale, across = s * size / voxel;
    if ((largestOnly || s >= lo) && s <= hi)
      continue;
    char text[400];
    std::snprintf(text, sizeof text,
      "pose %zu: scale %g makes the clip shape %g voxels across (%g world units at spacing "
      "%g); %s; the scale must lie in [%g, %g] for this shape and volume",
      i, s, across, s * size, voxel,
      s < lo ? "under half a voxel it covers no depth-map pixel and clips nothing"
             : "over 2^23 voxels the depth maps' float32 depths cannot resolve a voxel",
      lo, hi);
    error = text;
    return false;
  }
  return true;
}
}
