// Helpers shared by the filter tests: data paths, error capture, checks.
#ifndef caoFilterTestUtilities_h
#define caoFilterTestUtilities_h

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkObject.h"
#include "vtkPointData.h"
#include "vtkSLCReader.h"
#include "vtkSmartPointer.h"

#include "vtkCAOInput.h"

#include <algorithm>
#include <random>
#include <vector>
#include <cstdio>
#include <cstring>
#include <string>

#include "caoTestUtilities.h" // CAO_CHECK, shared with the kernel tests

namespace caotest
{
/// The exactness tests' pose suite: `count` random poses around and
/// through the volume (translation, rotation, scale 0.5..1.6), then poses
/// that graze a face, touch a corner, sit in the clipping camera's margin,
/// leave the volume, cover it whole, and sit at its centre.
inline std::vector<vtkCAO::Pose> MakePoses(const double bounds[6], double size, unsigned seed, int count)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  const double c[3] = { 0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]),
    0.5 * (bounds[4] + bounds[5]) };
  const double e[3] = { bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4] };
  std::vector<vtkCAO::Pose> poses;
  for (int i = 0; i < count; ++i)
  {
    vtkCAO::Pose p;
    for (int d = 0; d < 3; ++d)
    {
      p.translation[d] = bounds[2 * d] - 0.35 * e[d] + 1.7 * e[d] * uni(rng);
      p.rotation[d] = 360.0 * uni(rng);
    }
    p.scale = 0.5 + 1.1 * uni(rng);
    poses.push_back(p);
  }
  // Special poses. Grazing: the shape's extreme point at the volume's face.
  vtkCAO::Pose graze;
  graze.translation = { bounds[1] + size, c[1], c[2] };
  poses.push_back(graze);
  // Touching a corner region diagonally, half a voxel away.
  vtkCAO::Pose touch;
  touch.translation = { bounds[0] - size + 0.5, bounds[2] - 0.5, c[2] };
  poses.push_back(touch);
  // In the camera margin: the mesh is outside, its dilation reaches inside.
  vtkCAO::Pose margin;
  margin.translation = { c[0], bounds[3] + size + 2.0, c[2] };
  poses.push_back(margin);
  // Leaving: far away.
  vtkCAO::Pose away;
  away.translation = { bounds[1] + 3 * e[0], c[1], c[2] };
  poses.push_back(away);
  // Covering the whole volume.
  vtkCAO::Pose cover;
  cover.translation = { c[0], c[1], c[2] };
  cover.scale = 3.0 * std::max({ e[0], e[1], e[2] }) / size;
  poses.push_back(cover);
  // Centred, unrotated, unit scale.
  vtkCAO::Pose centre;
  centre.translation = { c[0], c[1], c[2] };
  poses.push_back(centre);
  return poses;
}

/// The "-D DIR" argument VTK test drivers use for the data directory.
inline std::string DataDirectory(int argc, char* argv[])
{
  for (int i = 1; i + 1 < argc; ++i)
    if (std::strcmp(argv[i], "-D") == 0)
      return argv[i + 1];
  return "Data";
}

inline vtkSmartPointer<vtkImageData> ReadSLC(const std::string& path)
{
  vtkNew<vtkSLCReader> r;
  r->SetFileName(path.c_str());
  r->Update();
  auto out = vtkSmartPointer<vtkImageData>::New();
  out->ShallowCopy(r->GetOutput());
  return out;
}

/// Counts error and warning events of the objects it watches.
struct EventCounter
{
  int errors = 0, warnings = 0;
  std::string lastError;
  vtkNew<vtkCallbackCommand> callback;
  EventCounter()
  {
    callback->SetClientData(this);
    callback->SetCallback([](vtkObject*, unsigned long id, void* self, void* data) {
      auto* c = static_cast<EventCounter*>(self);
      if (id == vtkCommand::ErrorEvent)
      {
        ++c->errors;
        c->lastError = data ? static_cast<const char*>(data) : "";
      }
      else
        ++c->warnings;
    });
  }
  void Watch(vtkObject* o)
  {
    o->AddObserver(vtkCommand::ErrorEvent, callback);
    o->AddObserver(vtkCommand::WarningEvent, callback);
  }
  void Reset()
  {
    errors = warnings = 0;
    lastError.clear();
  }
};

inline double Field(vtkDataObject* d, const char* name, int component)
{
  vtkDataArray* a = d->GetFieldData()->GetArray(name);
  return a ? a->GetComponent(0, component) : -1.0;
}

/// Bitwise equality of two arrays' contents.
inline bool SameBits(vtkDataArray* a, vtkDataArray* b)
{
  if (!a || !b || a->GetDataType() != b->GetDataType() ||
    a->GetNumberOfValues() != b->GetNumberOfValues())
    return false;
  return std::memcmp(a->GetVoidPointer(0), b->GetVoidPointer(0),
           static_cast<std::size_t>(a->GetNumberOfValues()) * a->GetDataTypeSize()) == 0;
}
}

#endif
