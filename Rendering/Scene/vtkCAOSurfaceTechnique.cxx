#include "vtkCAOSurfaceTechnique.h"

#include <algorithm>
#include <memory>
#include <mutex>

namespace vtkCAO
{
// The built-ins, each in its own file under Techniques/.
void RegisterVoxelConesTechnique();
void RegisterHBAOTechnique();
void RegisterVolumetricAOTechnique();

namespace
{
struct Registry
{
  std::mutex mutex;
  std::vector<std::unique_ptr<SurfaceTechnique>> techniques; // (pointers stay valid)
};

Registry& TheRegistry()
{
  static Registry registry;
  return registry;
}

bool Add(const SurfaceTechnique& technique, std::string* error)
{
  const auto fail = [error](const std::string& why) {
    if (error)
      *error = why;
    return false;
  };
  if (technique.method < 1)
    return fail("a surface technique's Method value must be 1 or more (0 is None); got " +
      std::to_string(technique.method));
  if (technique.name.empty() || !technique.cpu)
    return fail("a surface technique needs a name and a CPU step");
  Registry& r = TheRegistry();
  std::lock_guard<std::mutex> lock(r.mutex);
  for (const auto& t : r.techniques)
    if (t->method == technique.method)
      return fail("Method " + std::to_string(technique.method) + " is taken (by " + t->name + ")");
  r.techniques.push_back(std::make_unique<SurfaceTechnique>(technique));
  std::sort(r.techniques.begin(), r.techniques.end(),
    [](const auto& a, const auto& b) { return a->method < b->method; });
  return true;
}

void RegisterBuiltIns()
{
  static std::once_flag once;
  std::call_once(once, [] {
    RegisterVoxelConesTechnique();
    RegisterHBAOTechnique();
    RegisterVolumetricAOTechnique();
  });
}
}

bool RegisterBuiltIn(const SurfaceTechnique& technique)
{
  return Add(technique, nullptr);
}

bool RegisterSurfaceTechnique(const SurfaceTechnique& technique, std::string* error)
{
  RegisterBuiltIns();
  return Add(technique, error);
}

const SurfaceTechnique* FindSurfaceTechnique(int method)
{
  RegisterBuiltIns();
  Registry& r = TheRegistry();
  std::lock_guard<std::mutex> lock(r.mutex);
  for (const auto& t : r.techniques)
    if (t->method == method)
      return t.get();
  return nullptr;
}

std::string SurfaceTechniqueList()
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
