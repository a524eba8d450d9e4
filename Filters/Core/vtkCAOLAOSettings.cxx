#include "vtkCAOLAOSettings.h"

#include "vtkStringArray.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"

#include <cmath>
#include <string>

namespace vtkCAO
{
namespace
{
const char* const RunNames[] = { "Rays", "Step", "ScalarOpacityUnitDistance", "Milliseconds" };
}

void WriteLAOSettings(vtkFieldData* fd, const cao::LAOSettings& resolved, const LAORun& run)
{
  int count = 0;
  const cao::LAOSettingInfo* table = cao::LAOSettingTable(count);
  vtkNew<vtkDoubleArray> a;
  a->SetName(LAOSettingsName);
  a->SetNumberOfComponents(count + 4);
  cao::LAOSettings recorded = resolved;
  recorded.samples = run.samples;
  recorded.quality = run.quality;
  for (int c = 0; c < count; ++c)
  {
    a->SetComponentName(c, table[c].name);
  }
  for (int c = 0; c < 4; ++c)
  {
    a->SetComponentName(count + c, RunNames[c]);
  }
  a->SetNumberOfTuples(1);
  for (int c = 0; c < count; ++c)
  {
    a->SetComponent(0, c, cao::GetLAOSetting(recorded, table[c].name));
  }
  const double extra[4] = { static_cast<double>(run.rays), run.step, run.unitDistance,
    run.milliseconds };
  for (int c = 0; c < 4; ++c)
  {
    a->SetComponent(0, count + c, extra[c]);
  }
  fd->AddArray(a);
}

void WriteLAOUpdate(
  vtkFieldData* fd, const std::string& reason, std::int64_t changed, std::int64_t recomputed)
{
  vtkNew<vtkStringArray> why;
  why->SetName("LAOUpdate");
  why->InsertNextValue(reason);
  fd->AddArray(why);
  vtkNew<vtkDoubleArray> counts;
  counts->SetName("LAOUpdateVoxels");
  counts->SetNumberOfComponents(2);
  counts->SetComponentName(0, "ChangedVoxels");
  counts->SetComponentName(1, "RecomputedVoxels");
  const double values[2] = { static_cast<double>(changed), static_cast<double>(recomputed) };
  counts->InsertNextTuple(values);
  fd->AddArray(counts);
}

bool ReadLAOSettings(vtkFieldData* fd, cao::LAOSettings& settings, LAORun* run)
{
  LAORun r;
  cao::LAOSettings s;
  vtkDataArray* a = fd ? fd->GetArray(LAOSettingsName) : nullptr;
  if (a && a->GetNumberOfTuples() >= 1)
  {
    bool any = false;
    for (int c = 0; c < a->GetNumberOfComponents(); ++c)
    {
      const char* name = a->GetComponentName(c);
      if (!name)
        continue;
      const double v = a->GetComponent(0, c);
      const std::string n = name;
      if (cao::SetLAOSetting(s, n, v))
        any = true;
      else if (n == "Rays")
        r.rays = static_cast<int>(v);
      else if (n == "Step")
        r.step = v;
      else if (n == "ScalarOpacityUnitDistance")
        r.unitDistance = v;
      else if (n == "Milliseconds")
        r.milliseconds = v;
      else if (n == "QualityPreset") // the quality's name before it was one vocabulary
        s.quality = static_cast<cao::Quality>(static_cast<int>(v));
    }
    if (!any)
      return false;
  }
  else
  {
    // The predecessor: RayPattern, Rays, Samples, Reach, Step, UnitDistance,
    // FibonacciRays, Milliseconds[, StartOffset, RayVariation, Quality].
    a = fd ? fd->GetArray(LegacyLAOParametersName) : nullptr;
    const int n = a ? a->GetNumberOfComponents() : 0;
    if (!a || a->GetNumberOfTuples() < 1 || (n != 11 && n != 8))
      return false;
    double v[11] = { 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0 };
    a->GetTuple(0, v);
    s.pattern = static_cast<cao::RayPattern>(static_cast<int>(v[0]));
    r.rays = static_cast<int>(v[1]);
    s.samples = static_cast<int>(v[2]);
    s.reach = v[3];
    r.step = v[4];
    r.unitDistance = v[5];
    s.fibonacciRays = static_cast<int>(v[6]);
    r.milliseconds = v[7];
    s.startOffset = v[8];
    s.variation = static_cast<cao::RayVariation>(static_cast<int>(v[9]));
    s.quality = static_cast<cao::Quality>(static_cast<int>(v[10]));
  }
  // The recorded values are the ones in effect: rebuild from them as given.
  r.quality = s.quality;
  s.quality = cao::Quality::Custom;
  r.samples = s.samples;
  settings = s;
  if (run)
    *run = r;
  return true;
}

void PrintLAOSettings(ostream& os, vtkIndent indent, const cao::LAOSettings& s)
{
  os << indent << "RayPattern: " << cao::RayPatternName(s.pattern) << "\n";
  os << indent << "NumberOfRays: " << s.fibonacciRays << "\n";
  os << indent << "Reach: " << s.reach << (s.reach == 0.0 ? " (8 voxels)" : "") << "\n";
  os << indent << "NumberOfSamples: " << s.samples
     << (s.samples == 0 ? " (SampleDensity per voxel)" : "") << "\n";
  os << indent << "SampleDensity: " << s.sampleDensity << "\n";
  os << indent << "StartOffset: " << s.startOffset << "\n";
  os << indent << "RayVariation: " << cao::RayVariationName(s.variation) << "\n";
  os << indent << "Quality: " << cao::QualityName(s.quality) << "\n";
}
}
