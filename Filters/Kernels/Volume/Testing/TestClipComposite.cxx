// Several clip shapes as one (caoClipComposite) against their exact shapes
// (ClipShape::Composite), VTK-free:
//  - the weights and threshold of every mode mix;
//  - the depth maps of 8 posed spheres (one mirrored, one wound inward),
//    of 3 probes, and of 2 probes less 2 subtractions hold, along every
//    pixel ray, exactly the points the exact combination calls inside
//    (points within the tessellation's deviation of a surface excluded);
//  - negative controls: the same maps made without the weights (plain
//    nonzero winding) disagree with the exact shape in every scene;
//  - bad input (no parts, too many, an open mesh, a singular pose, an
//    unknown mode) is refused with the reason.
#include "caoClipComposite.h"
#include "caoClipGeometry.h"
#include "caoGPULayout.h"
#include "caoTestUtilities.h"

#include <cmath>
#include <string>
#include <vector>

namespace
{
struct Sphere
{
  double centre[3];
  double radius;
  int mode;
  bool mirror = false;  // pose mirrors x
  bool inward = false;  // triangles wound inward
};

struct Scene
{
  std::vector<std::vector<double>> points;
  std::vector<std::vector<std::int64_t>> triangles;
  std::vector<cao::ClipPart> parts;
  double deviation = 0.0; // common units
};

void MakeScene(const std::vector<Sphere>& spheres, Scene& scene)
{
  const int n = 48;
  scene.points.resize(spheres.size());
  scene.triangles.resize(spheres.size());
  for (std::size_t i = 0; i < spheres.size(); ++i)
  {
    caotest::UVSphere(1.0, n, scene.points[i], scene.triangles[i]);
    if (spheres[i].inward)
      for (std::size_t t = 0; t < scene.triangles[i].size(); t += 3)
        std::swap(scene.triangles[i][t + 1], scene.triangles[i][t + 2]);
  }
  for (std::size_t i = 0; i < spheres.size(); ++i)
  {
    cao::ClipPart part;
    part.mesh = cao::ViewMesh(scene.points[i], scene.triangles[i]);
    const double r = spheres[i].radius;
    const double A[12] = { spheres[i].mirror ? -r : r, 0, 0, spheres[i].centre[0], 0, r, 0,
      spheres[i].centre[1], 0, 0, r, spheres[i].centre[2] };
    std::copy(A, A + 12, part.localToCommon);
    part.mode = spheres[i].mode;
    scene.parts.push_back(part);
    // A UV sphere's faces lie inside the sphere by at most its sagitta.
    scene.deviation = std::max(scene.deviation, 2.0 * r * (1.0 - std::cos(3.141592653589793 / n)));
  }
}

cao::ClipShape ExactShape(const std::vector<Sphere>& spheres)
{
  std::vector<cao::ClipShapePart> parts;
  for (const Sphere& s : spheres)
  {
    cao::ClipShapePart p;
    p.shape = cao::ClipShape::Sphere(1.0);
    const double r = s.radius;
    const double A[12] = { s.mirror ? -r : r, 0, 0, s.centre[0], 0, r, 0, s.centre[1], 0, 0, r,
      s.centre[2] };
    std::copy(A, A + 12, p.localToCommon);
    p.mode = s.mode;
    parts.push_back(std::move(p));
  }
  return cao::ClipShape::Composite(std::move(parts));
}

struct Agreement
{
  long long inside = 0, outside = 0, wrong = 0;
};

/// Rasterise `mesh` over [-6, 6]^2 (z from -6) and compare every pixel ray,
/// sampled every 0.05, with the exact shape away from its surface.
bool Compare(const cao::TriangleMesh& mesh, const cao::ClipShape& exact, double margin,
  Agreement& a, cao::ClipDepthMaps& maps, std::string& error)
{
  cao::ClipCamera cam;
  cam.origin[0] = cam.origin[1] = cam.origin[2] = -6.0;
  cam.pixelSize[0] = cam.pixelSize[1] = 0.1;
  cam.width = cam.height = 120;
  cam.layers = 8;
  if (!cao::RasterizeDepthLayers(cam, mesh, maps, error))
    return false;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x)
      for (int k = 0; k < 240; ++k)
      {
        const double z = 0.05 * k + 0.025;
        const double p[3] = { -6.0 + 0.1 * (x + 0.5), -6.0 + 0.1 * (y + 0.5), -6.0 + z };
        const double d = exact.SignedDistance(p);
        if (std::fabs(d) <= margin)
          continue;
        bool inMaps = false;
        for (int l = 0; l < cam.layers; ++l)
        {
          const std::size_t i = maps.Index(l, x, y);
          inMaps = inMaps || (maps.front[i] <= z && z <= maps.back[i]);
        }
        (d < 0 ? a.inside : a.outside)++;
        if (inMaps != (d < 0))
          ++a.wrong;
      }
  return true;
}
}

int TestClipComposite(int, char*[])
{
  using cao::layout::CAO_MODE_PROBE;
  using cao::layout::CAO_MODE_SUBTRACT;
  // 1. The combination rule.
  {
    const cao::ClipCombination u = cao::CombineClipModes(0, 8);
    CAO_CHECK(u.mode == CAO_MODE_SUBTRACT && u.subtractionWeight == 1 && u.minimumWinding == 1,
      "union of subtractions");
    const cao::ClipCombination i = cao::CombineClipModes(3, 0);
    CAO_CHECK(i.mode == CAO_MODE_PROBE && i.probeWeight == 1 && i.minimumWinding == 3,
      "intersection of probes");
    const cao::ClipCombination m = cao::CombineClipModes(2, 2);
    CAO_CHECK(m.mode == CAO_MODE_PROBE && m.subtractionWeight == -3 && m.minimumWinding == 2,
      "probes less subtractions");
  }

  // 2. Scenes against their exact shapes, with negative controls.
  const std::vector<std::vector<Sphere>> scenes = {
    // 8 subtracting spheres, chained and overlapping, one mirrored, one inward.
    { { { -3.5, -3.0, 0.0 }, 1.2, CAO_MODE_SUBTRACT }, { { -2.2, -2.4, 0.3 }, 1.0, CAO_MODE_SUBTRACT },
      { { -1.0, -1.5, -0.2 }, 1.3, CAO_MODE_SUBTRACT, true }, { { 0.5, -0.5, 0.4 }, 0.9, CAO_MODE_SUBTRACT },
      { { 1.5, 0.8, 0.0 }, 1.4, CAO_MODE_SUBTRACT, false, true }, { { 3.0, 1.5, -0.5 }, 1.0, CAO_MODE_SUBTRACT },
      { { 3.4, 3.2, 0.5 }, 1.1, CAO_MODE_SUBTRACT }, { { -2.5, 3.0, 0.0 }, 1.5, CAO_MODE_SUBTRACT } },
    // 3 probes: a lens-shaped intersection.
    { { { -0.8, 0.0, 0.0 }, 2.5, CAO_MODE_PROBE }, { { 0.8, 0.0, 0.0 }, 2.5, CAO_MODE_PROBE, true },
      { { 0.0, 0.9, 0.3 }, 2.2, CAO_MODE_PROBE, false, true } },
    // 2 probes less 2 subtractions.
    { { { -1.0, 0.0, 0.0 }, 3.0, CAO_MODE_PROBE }, { { 1.0, 0.0, 0.0 }, 3.0, CAO_MODE_PROBE },
      { { 0.0, 0.0, 0.0 }, 1.2, CAO_MODE_SUBTRACT }, { { 0.0, 1.8, 1.0 }, 1.0, CAO_MODE_SUBTRACT, false,
                                                   true } },
  };
  const char* names[] = { "8 subtractions", "3 probes", "2 probes less 2 subtractions" };
  for (std::size_t s = 0; s < scenes.size(); ++s)
  {
    Scene scene;
    MakeScene(scenes[s], scene);
    cao::CompositeClipMesh composite;
    std::string error;
    CAO_CHECK(cao::BuildCompositeClipMesh(scene.parts, composite, error), "%s: %s", names[s],
      error.c_str());
    const cao::ClipShape exact = ExactShape(scenes[s]);
    const double margin = scene.deviation + 1e-9;
    Agreement a;
    cao::ClipDepthMaps maps;
    CAO_CHECK(Compare(composite.View(), exact, margin, a, maps, error), "%s: %s", names[s],
      error.c_str());
    std::printf("%-30s inside %lld, outside %lld, wrong %lld; overflow %lld, unmatched %lld\n",
      names[s], a.inside, a.outside, a.wrong, static_cast<long long>(maps.overflowPixels),
      static_cast<long long>(maps.unmatchedPixels));
    CAO_CHECK(a.wrong == 0 && a.inside > 1000 && a.outside > 1000 && maps.overflowPixels == 0 &&
        maps.unmatchedPixels == 0,
      "%s: %lld samples disagree with the exact shape", names[s], a.wrong);
    // Negative control: the same triangles with the plain winding rule.
    cao::TriangleMesh plain = cao::ViewMesh(composite.points, composite.triangles);
    Agreement b;
    CAO_CHECK(Compare(plain, exact, margin, b, maps, error), "%s", error.c_str());
    std::printf("%-30s unweighted: wrong %lld\n", names[s], b.wrong);
    CAO_CHECK(b.wrong > 100, "%s: the unweighted control should disagree (%lld)", names[s],
      b.wrong);
  }

  // 3. The exact composite's distances: exact sign, never above the truth.
  {
    const cao::ClipShape u = ExactShape({ { { 0, 0, 0 }, 1.0, CAO_MODE_SUBTRACT },
      { { 1.5, 0, 0 }, 1.0, CAO_MODE_SUBTRACT } });
    const double mid[3] = { 0.75, 0, 0 }, far[3] = { 5, 0, 0 };
    CAO_CHECK(u.SignedDistance(mid) < 0.0 && std::fabs(u.SignedDistance(far) - 2.5) < 1e-12 &&
        std::string(u.Name()) == "composite",
      "union distances");
    const cao::ClipShape s = ExactShape({ { { 0, 0, 0 }, 2.0, CAO_MODE_PROBE } });
    const double in[3] = { 0.5, 0, 0 };
    CAO_CHECK(std::fabs(s.SignedDistance(in) + 1.5) < 1e-12, "a scaled probe's distance");
  }

  // 4. Bad input.
  {
    std::vector<double> pts;
    std::vector<std::int64_t> tris;
    caotest::UVSphere(1.0, 16, pts, tris);
    cao::ClipPart good;
    good.mesh = cao::ViewMesh(pts, tris);
    cao::CompositeClipMesh out;
    std::string error;
    CAO_CHECK(!cao::BuildCompositeClipMesh({}, out, error) &&
        error.find("1 to 32") != std::string::npos,
      "no parts: %s", error.c_str());
    CAO_CHECK(!cao::BuildCompositeClipMesh(std::vector<cao::ClipPart>(33, good), out, error) &&
        error.find("not 33") != std::string::npos,
      "33 parts: %s", error.c_str());
    cao::ClipPart singular = good;
    singular.localToCommon[10] = 0.0;
    CAO_CHECK(!cao::BuildCompositeClipMesh({ good, singular }, out, error) &&
        error.find("clip shape 1 has a singular pose") != std::string::npos,
      "singular: %s", error.c_str());
    cao::ClipPart nan = good;
    nan.localToCommon[3] = std::nan("");
    CAO_CHECK(!cao::BuildCompositeClipMesh({ nan }, out, error) &&
        error.find("not finite") != std::string::npos,
      "NaN pose: %s", error.c_str());
    cao::ClipPart mode = good;
    mode.mode = 7;
    CAO_CHECK(!cao::BuildCompositeClipMesh({ mode }, out, error) &&
        error.find("unknown mode 7") != std::string::npos,
      "mode: %s", error.c_str());
    std::vector<std::int64_t> open(tris.begin(), tris.end() - 3);
    cao::ClipPart hole = good;
    hole.mesh = cao::ViewMesh(pts, open);
    CAO_CHECK(!cao::BuildCompositeClipMesh({ good, hole }, out, error) &&
        error.find("clip shape 1") != std::string::npos,
      "open: %s", error.c_str());
    std::printf("open part refused: %s\n", error.c_str());
    CAO_CHECK(cao::BuildCompositeClipMesh(std::vector<cao::ClipPart>(32, good), out, error) &&
        out.weights.size() == 32 * tris.size() / 3,
      "32 parts: %s", error.c_str());
  }
  return 0;
}
