/**
 * vtkCAOTechniqueRegistry.h — the registry every kind of technique shares
 * (surfaces: vtkCAOSurfaceTechnique.h; lines: vtkCAOLineTechnique.h): the
 * techniques of one kind by their Method value, 1 or more (0 is None),
 * each value once, kept in value order, the built-ins registered first.
 * Private to the module.
 */
#ifndef vtkCAOTechniqueRegistry_h
#define vtkCAOTechniqueRegistry_h

#include <algorithm>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace vtkCAO
{
/// `Technique` has `method`, `name` and a `cpu` step (the required one).
template <typename Technique>
class TechniqueRegistry
{
public:
  /// `kind` in messages ("surface"), `value` the pass's property that takes
  /// the method values ("Method"); `builtIns` registers the built-ins (with
  /// AddBuiltIn, never Add, Find or List, which would wait on themselves),
  /// once, before any other call answers.
  TechniqueRegistry(const char* kind, const char* value, std::function<void()> builtIns)
    : Kind(kind)
    , Value(value)
    , BuiltIns(std::move(builtIns))
  {
  }

  /// False, saying why in `error`, when the method is not 1 or more, is
  /// taken, or the technique has no name or no CPU step.
  bool Add(const Technique& technique, std::string* error)
  {
    this->EnsureBuiltIns();
    return this->Insert(technique, error);
  }
  /// Only from the built-ins' callback (else refused: a value taken before
  /// the built-ins register would push one out).
  bool AddBuiltIn(const Technique& technique, std::string* error = nullptr)
  {
    if (!this->RegisteringBuiltIns)
    {
      if (error)
        *error = std::string("only the built-in ") + this->Kind + " techniques register as built-ins";
      return false;
    }
    return this->Insert(technique, error);
  }


  /// The technique of `method`, or null (the pointer stays valid).
  const Technique* Find(int method)
  {
    return this->FindIf([method](const Technique& t) { return t.method == method; });
  }
  /// The technique named `name` ("vct"), or null.
  const Technique* FindNamed(const std::string& name)
  {
    return this->FindIf([&name](const Technique& t) { return t.name == name; });
  }
  /// "1 vct, 2 hbao": values and names in value order.
  std::string List()
  {
    this->EnsureBuiltIns();
    std::lock_guard<std::mutex> lock(this->Mutex);
    std::string list;
    for (const auto& t : this->Techniques)
      list += (list.empty() ? "" : ", ") + std::to_string(t->method) + " " + t->name;
    return list;
  }

private:
  const Technique* FindIf(const std::function<bool(const Technique&)>& match)
  {
    this->EnsureBuiltIns();
    std::lock_guard<std::mutex> lock(this->Mutex);
    for (const auto& t : this->Techniques)
      if (match(*t))
        return t.get();
    return nullptr;
  }
  bool Insert(const Technique& technique, std::string* error)
  {
    const auto fail = [error](const std::string& why) {
      if (error)
        *error = why;
      return false;
    };
    if (technique.method < 1)
      return fail(std::string("a ") + this->Kind + " technique's " + this->Value +
        " value must be 1 or more (0 is None); got " + std::to_string(technique.method));
    if (technique.name.empty() || !technique.cpu)
      return fail(std::string("a ") + this->Kind + " technique needs a name and a CPU step");
    std::lock_guard<std::mutex> lock(this->Mutex);
    for (const auto& t : this->Techniques)
      if (t->method == technique.method)
        return fail(std::string(this->Value) + " " + std::to_string(technique.method) + " is taken (by " +
          t->name + ")");
    auto copy = std::make_unique<Technique>(technique);
    if (copy->label.empty())
      copy->label = copy->name; // (messages name it)
    this->Techniques.push_back(std::move(copy));
    std::sort(this->Techniques.begin(), this->Techniques.end(),
      [](const auto& a, const auto& b) { return a->method < b->method; });
    return true;
  }

  void EnsureBuiltIns()
  {
    std::call_once(this->Once, [this] {
      this->RegisteringBuiltIns = true;
      this->BuiltIns();
      this->RegisteringBuiltIns = false;
    });
  }

  const char* Kind;
  const char* Value;
  bool RegisteringBuiltIns = false; ///< (set inside the once-callback only)
  std::function<void()> BuiltIns;
  std::once_flag Once;
  std::mutex Mutex;
  std::vector<std::unique_ptr<Technique>> Techniques;
};
}

#endif
