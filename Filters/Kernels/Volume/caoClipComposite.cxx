#include "caoClipComposite.h"

#include "caoClipCamera.h"
#include "caoGPULayout.h"

#include <cmath>

namespace cao
{
ClipCombination CombineClipModes(int probes, int subtractions)
{
  ClipCombination c;
  c.probes = probes;
  c.subtractions = subtractions;
  if (probes == 0)
  {
    c.mode = layout::CAO_MODE_SUBTRACT;
    c.minimumWinding = 1; // the union of the subtracting parts
  }
  else
  {
    // Kept: winding of the probes == P and no subtracting part around. A
    // point in a subtracting part has winding at most P - (P + 1) < P.
    c.mode = layout::CAO_MODE_PROBE;
    c.subtractionWeight = -(probes + 1);
    c.minimumWinding = probes;
  }
  return c;
}

TriangleMesh CompositeClipMesh::View() const
{
  TriangleMesh m = ViewMesh(this->points, this->triangles);
  m.weights = this->weights.data();
  m.minimumWinding = this->combination.minimumWinding;
  return m;
}

namespace
{
double Determinant3(const double* A)
{
  return A[0] * (A[5] * A[10] - A[6] * A[9]) - A[1] * (A[4] * A[10] - A[6] * A[8]) +
    A[2] * (A[4] * A[9] - A[5] * A[8]);
}
}

bool BuildCompositeClipMesh(
  const std::vector<ClipPart>& parts, CompositeClipMesh& out, std::string& error)
{
  out = CompositeClipMesh();
  const int n = static_cast<int>(parts.size());
  if (n < 1 || n > MaximumClipParts)
  {
    error = "a composite clip takes 1 to " + std::to_string(MaximumClipParts) +
      " shapes, not " + std::to_string(n);
    return false;
  }
  int probes = 0, subtractions = 0;
  for (int i = 0; i < n; ++i)
  {
    const int mode = parts[i].mode;
    if (mode != layout::CAO_MODE_SUBTRACT && mode != layout::CAO_MODE_PROBE)
    {
      error = "clip shape " + std::to_string(i) + " has an unknown mode " + std::to_string(mode) +
        " (0 subtraction or 1 probing)";
      return false;
    }
    (mode == layout::CAO_MODE_PROBE ? probes : subtractions)++;
  }
  out.combination = CombineClipModes(probes, subtractions);
  for (int i = 0; i < n; ++i)
  {
    const ClipPart& part = parts[i];
    const std::string name = "clip shape " + std::to_string(i);
    const double* A = part.localToCommon;
    for (int k = 0; k < 12; ++k)
      if (!std::isfinite(A[k]))
      {
        error = name + " has a pose that is not finite";
        return false;
      }
    const double det = Determinant3(A);
    if (!(std::fabs(det) > 0.0) || !std::isfinite(det))
    {
      error = name + " has a singular pose";
      return false;
    }
    ClosedMeshCheck check;
    std::string why;
    if (!CheckClosedMesh(part.mesh, check, why))
    {
      error = name + ": " + why;
      return false;
    }
    // Outward in the common frame: the mesh's own orientation times the
    // pose's handedness.
    const bool outward = (check.signedVolume > 0.0) == (det > 0.0);
    int weight = part.mode == layout::CAO_MODE_PROBE ? out.combination.probeWeight
                                                     : out.combination.subtractionWeight;
    if (!outward)
      weight = -weight;
    const std::int64_t first = static_cast<std::int64_t>(out.points.size() / 3);
    for (std::int64_t p = 0; p < part.mesh.numberOfPoints; ++p)
    {
      const double* q = part.mesh.points + 3 * p;
      for (int r = 0; r < 3; ++r)
        out.points.push_back(A[4 * r] * q[0] + A[4 * r + 1] * q[1] + A[4 * r + 2] * q[2] +
          A[4 * r + 3]);
    }
    for (std::int64_t t = 0; t < 3 * part.mesh.numberOfTriangles; ++t)
      out.triangles.push_back(first + part.mesh.triangles[t]);
    out.weights.insert(out.weights.end(), static_cast<std::size_t>(part.mesh.numberOfTriangles),
      weight);
  }
  return true;
}
}
