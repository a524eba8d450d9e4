// The half-space calibration value (HalfSpaceAO): its closed form equals
// the march itself on a voxelised opaque half-space, averaged the same way
// (six faces, both layers, two face positions so every variant appears),
// for every pattern and variation; the 6-ray value worked by hand; and a
// face one layer off gives a clearly different value (negative control).
// The general form (matter of any opacity, any depth) equals the march on
// a half-space of that opacity at layers 0 to 4, and the table the ray
// caster reads holds it.
#include "caoLAO.h"
#include "caoTestUtilities.h"

#include <cmath>
#include <vector>

namespace
{
/// The mean LAO (LAOVoxelDouble) on the faces of opaque half-spaces whose
/// first full layer is `shift` layers past the layer HalfSpaceAO assumes.
double MarchedHalfSpace(const cao::LAOPlan& plan, const cao::VolumeGeometry& g, int shift,
  float opacity = 1.0f, int onlyLayer = -1)
{
  std::vector<float> a(static_cast<std::size_t>(g.NumberOfVoxels()));
  double total = 0.0;
  int count = 0;
  for (int axis = 0; axis < 3; ++axis)
    for (int sign = -1; sign <= 1; sign += 2)
      for (int c = 11; c <= 12; ++c) // two face positions: every variant parity
      {
        // Full: the layers beyond c (+ shift) in the direction `sign`.
        for (int k = 0; k < g.dims[2]; ++k)
          for (int j = 0; j < g.dims[1]; ++j)
            for (int i = 0; i < g.dims[0]; ++i)
            {
              const int x = axis == 0 ? i : axis == 1 ? j : k;
              const int depth = sign * (x - c) - shift;
              a[i + g.dims[0] * (j + std::size_t(g.dims[1]) * k)] = depth >= 1 ? opacity : 0.0f;
            }
        for (int layer = onlyLayer < 0 ? 0 : onlyLayer; layer < (onlyLayer < 0 ? 2 : onlyLayer + 1);
             ++layer)
          for (int u = 0; u < 2; ++u)
            for (int w = 0; w < 2; ++w)
            {
              int p[3];
              p[axis] = c + sign * layer;
              p[(axis + 1) % 3] = 12 + u;
              p[(axis + 2) % 3] = 12 + w;
              total += cao::LAOVoxelDouble(plan, a.data(), p[0], p[1], p[2]);
              ++count;
            }
      }
  return total / count;
}
}

int TestHalfSpaceAO(int, char*[])
{
  cao::VolumeGeometry g;
  for (int d = 0; d < 3; ++d)
    g.dims[d] = 25;
  g.spacing[0] = 1.0;
  g.spacing[1] = 0.8;
  g.spacing[2] = 1.3;
  const cao::RayPattern patterns[] = { cao::RayPattern::Rays6, cao::RayPattern::Rays14,
    cao::RayPattern::Rays26, cao::RayPattern::Rays54, cao::RayPattern::Rubiks54,
    cao::RayPattern::Fibonacci };
  const cao::RayVariation variations[] = { cao::RayVariation::None, cao::RayVariation::Rotate,
    cao::RayVariation::Jitter, cao::RayVariation::RotateJitter };
  for (cao::RayPattern pattern : patterns)
    for (cao::RayVariation variation : variations)
      for (double offset : { 0.0, 0.5 })
      {
        cao::LAOSettings s = caotest::ExplicitSettings();
        s.pattern = pattern;
        s.fibonacciRays = 40;
        s.reach = 4.5;
        s.variation = variation;
        s.startOffset = offset;
        cao::LAOPlan plan;
        std::string error;
        CAO_CHECK(cao::BuildLAOPlan(g, s, plan, error), "%s", error.c_str());
        const double closed = cao::HalfSpaceAO(plan, 0.5);
        const double marched = MarchedHalfSpace(plan, g, 0);
        CAO_CHECK(std::fabs(closed - marched) < 1e-12,
          "pattern %d variation %d offset %g: closed form %.15g, march %.15g",
          static_cast<int>(pattern), static_cast<int>(variation), offset, closed, marched);
        CAO_CHECK(closed > 0.3 && closed < 0.7, "an open face is about half open: %g", closed);
        // Negative control: the face one layer further gives another value.
        const double shifted = MarchedHalfSpace(plan, g, 1);
        CAO_CHECK(std::fabs(shifted - closed) > 0.05,
          "a face one layer off should differ: %.6g vs %.6g", shifted, closed);
        // Matter of opacity 0.553 (0.8 per unit at half-voxel steps), layer
        // by layer into it: the general form, and the table at its steps.
        if (pattern == cao::RayPattern::Rays14 || pattern == cao::RayPattern::Fibonacci)
        {
          const std::vector<float> table = cao::HalfSpaceTable(plan);
          for (int layer = 0; layer <= 4; ++layer)
          {
            const double general = cao::HalfSpaceAO(plan, layer, 0.553);
            const double march = MarchedHalfSpace(plan, g, 0, 0.553f, layer);
            CAO_CHECK(std::fabs(general - march) < 1e-6,
              "pattern %d variation %d: layer %d of opacity 0.553: closed %.9g, march %.9g",
              static_cast<int>(pattern), static_cast<int>(variation), layer, general, march);
            const double at = table[static_cast<std::size_t>(layer) * CAO_HALF_SPACE_OPACITIES + 8];
            CAO_CHECK(std::fabs(at - cao::HalfSpaceAO(plan, layer, 0.5)) < 1e-6,
              "the table at layer %d, opacity 0.5: %.9g", layer, at);
          }
          CAO_CHECK(cao::HalfSpaceAO(plan, 3.0, 0.553) < cao::HalfSpaceAO(plan, 1.0, 0.553) &&
              cao::HalfSpaceAO(plan, 1.0, 0.3) > cao::HalfSpaceAO(plan, 1.0, 0.553),
            "deeper is darker, clearer matter lighter");
          // Negative control: opacity 1 is not the matter's own half-space.
          CAO_CHECK(std::fabs(cao::HalfSpaceAO(plan, 1.0, 1.0) -
                      MarchedHalfSpace(plan, g, 0, 0.553f, 1)) > 0.02,
            "an opaque half-space should differ from matter of opacity 0.553");
        }
      }

  // By hand: 6 rays, reach 8 voxels, 8 samples at (m - 1/2) voxels. The
  // last empty layer: the ray into the matter 1.5/8, the other five 1:
  // 0.864583; the first full layer: the ray out of it 4.5/8, the other five
  // 1/8: 0.197917; the face: their mean, 0.53125.
  {
    cao::VolumeGeometry unit;
    for (int d = 0; d < 3; ++d)
      unit.dims[d] = 25;
    cao::LAOSettings s = caotest::ExplicitSettings();
    s.pattern = cao::RayPattern::Rays6;
    s.reach = 8.0;
    cao::LAOPlan plan;
    std::string error;
    CAO_CHECK(cao::BuildLAOPlan(unit, s, plan, error), "%s", error.c_str());
    CAO_CHECK(plan.samples == 8, "samples %d", plan.samples);
    const double value = cao::HalfSpaceAO(plan, 0.5);
    CAO_CHECK(std::fabs(value - 0.53125) < 1e-12, "6 rays: %.15g, expected 0.53125", value);
    const cao::AOCalibration c = cao::SurfaceCalibration(plan);
    CAO_CHECK(std::fabs(c.openEmpty - 0.864583333333333) < 1e-12 &&
        std::fabs(c.openOpaque - 0.197916666666667) < 1e-12 && c.enclosed == 0.125,
      "6 rays: open %.15g / %.15g, enclosed %g", c.openEmpty, c.openOpaque, c.enclosed);
  }
  return 0;
}
