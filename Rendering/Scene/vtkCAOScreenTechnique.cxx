#include "vtkCAOScreenTechnique.h"

#include <algorithm>
#include <memory>
#include <mutex>

namespace vtkCAO
{
// The built-ins, each in its own file under Techniques/.
void RegisterHBAOTechnique();
void RegisterVolumetricAOTechnique();

namespace
{
struct Registry
{
  std::mutex mutex;
  std::vector<std::unique_ptr<ScreenTechnique>> techniques; // (pointers stay valid)
};

Registry& TheRegistry()
{
  static Registry registry;
  return registry;
}

bool Add(const ScreenTechnique& technique, std::string* error)
{
  const auto fail = [error](const std::string& why) {
    if (error)
      *error = why;
    return false;
  };
  if (technique.method <= 1)
    return fail("a screen-space technique's Method value must be above 1 (0 is None, 1 Voxel Cones); got " +
      std::to_string(technique.method));
  if (technique.name.empty() || !technique.cpu)
    return fail("a screen-space technique needs a name and a CPU step");
  Registry& r = TheRegistry();
  std::lock_guard<std::mutex> lock(r.mutex);
  for (const auto& t : r.techniques)
    if (t->method == technique.method)
      return fail("Method " + std::to_string(technique.method) + " is taken (by " + t->name + ")");
  r.techniques.push_back(std::make_unique<ScreenTechnique>(technique));
  std::sort(r.techniques.begin(), r.techniques.end(),
    [](const auto& a, const auto& b) { return a->method < b->method; });
  return true;
}

void RegisterBuiltIns()
{
  static std::once_flag once;
  std::call_once(once, [] {
    RegisterHBAOTechnique();
    RegisterVolumetricAOTechnique();
  });
}
}

bool RegisterBuiltIn(const ScreenTechnique& technique)
{
  return Add(technique, nullptr);
}

bool RegisterScreenTechnique(const ScreenTechnique& technique, std::string* error)
{
  RegisterBuiltIns();
  return Add(technique, error);
}

const ScreenTechnique* FindScreenTechnique(int method)
{
  RegisterBuiltIns();
  Registry& r = TheRegistry();
  std::lock_guard<std::mutex> lock(r.mutex);
  for (const auto& t : r.techniques)
    if (t->method == method)
      return t.get();
  return nullptr;
}

std::string ScreenTechniqueList()
{
  RegisterBuiltIns();
  Registry& r = TheRegistry();
  std::lock_guard<std::mutex> lock(r.mutex);
  std::string list;
  for (const auto& t : r.techniques)
    list += (list.empty() ? "" : ", ") + std::to_string(t->method) + " " + t->name;
  return list;
}
}
