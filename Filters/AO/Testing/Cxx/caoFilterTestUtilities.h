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

#include <cstdio>
#include <cstring>
#include <string>

#include "caoTestUtilities.h" // CAO_CHECK, shared with the kernel tests

namespace caotest
{
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
