#include "vtkContextualAOPass.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkCamera.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkSmartPointer.h"
#include "vtkFloatArray.h"
#include "vtkMapper.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderState.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"

#include "vtkCAOInput.h"

#include "caoSurfaceReference.h"
#include "caoVoxelConeTracing.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <vector>

vtkStandardNewMacro(vtkContextualAOPass);
vtkCxxSetObjectMacro(vtkContextualAOPass, DelegatePass, vtkRenderPass);

namespace
{
/// The polygonal pieces a mapper draws: its polydata input, or the polydata
/// leaves of a composite input (ParaView's geometry representations hand
/// their mapper a multiblock dataset).
std::vector<vtkPolyData*> Pieces(vtkMapper* mapper)
{
  std::vector<vtkPolyData*> pieces;
  vtkDataObject* input = mapper ? mapper->GetInputDataObject(0, 0) : nullptr;
  if (auto* poly = vtkPolyData::SafeDownCast(input))
    pieces.push_back(poly);
  else if (auto* composite = vtkCompositeDataSet::SafeDownCast(input))
  {
    vtkSmartPointer<vtkCompositeDataIterator> it;
    it.TakeReference(composite->NewIterator());
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
      if (auto* leaf = vtkPolyData::SafeDownCast(it->GetCurrentDataObject()))
        pieces.push_back(leaf);
  }
  pieces.erase(std::remove_if(pieces.begin(), pieces.end(),
                 [](vtkPolyData* p) { return p->GetNumberOfCells() == 0; }),
    pieces.end());
  return pieces;
}

double Since(std::chrono::steady_clock::time_point t)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}
}

struct vtkContextualAOPass::Internals
{
  // What the grid was built from: per actor its address, its data's address
  // and time, its matrix; then slices and the radius setting.
  std::vector<double> sceneKey;
  std::vector<std::vector<double>> points;
  std::vector<std::vector<std::int64_t>> triangles;
  cao::TriangleBVH bvh;
  cao::BitGrid grid;
  double radius = 0.0;
  int open = 0;
  int serial = 0; ///< grids built
  // What the AO image was made for: camera, viewport, settings, grid.
  std::vector<double> viewKey;
  cao::SurfaceFrame frame;
  int x0 = 0, y0 = 0;
  // The last frame.
  std::vector<std::string> stages, reasons;
  std::vector<double> ms;
  std::string error;
  std::int64_t combined = 0;
};

vtkContextualAOPass::vtkContextualAOPass()
  : Internal(new Internals)
{
  vtkRenderStepsPass* steps = vtkRenderStepsPass::New();
  this->SetDelegatePass(steps);
  steps->Delete();
}

vtkContextualAOPass::~vtkContextualAOPass()
{
  this->SetDelegatePass(nullptr);
}

void vtkContextualAOPass::ReleaseGraphicsResources(vtkWindow* w)
{
  if (this->DelegatePass)
    this->DelegatePass->ReleaseGraphicsResources(w);
}

int vtkContextualAOPass::GetNumberOfOpenMeshes() const
{
  return this->Internal->open;
}

double vtkContextualAOPass::GetPixelAO(int x, int y) const
{
  const cao::SurfaceFrame& f = this->Internal->frame;
  if (x < 0 || y < 0 || x >= f.width || y >= f.height)
    return -1.0;
  const double a = f.ao[static_cast<std::size_t>(y) * f.width + x];
  return std::isfinite(a) ? a : -1.0;
}

std::string vtkContextualAOPass::GetLastFrameStages() const
{
  std::string s;
  for (const std::string& stage : this->Internal->stages)
    s += (s.empty() ? "" : ",") + stage;
  return s;
}

std::string vtkContextualAOPass::GetLastFrameReport() const
{
  const Internals& p = *this->Internal;
  std::ostringstream o;
  o << "{\"frame\": " << this->FrameCount << ", \"method\": \""
    << (this->Method == VCT ? "vct" : "none") << "\", \"stages\": {";
  for (std::size_t i = 0; i < p.stages.size(); ++i)
    o << (i ? ", " : "") << "\"" << p.stages[i] << "\": " << p.ms[i];
  o << "}, \"reasons\": [";
  for (std::size_t i = 0; i < p.reasons.size(); ++i)
    o << (i ? ", " : "") << "\"" << p.reasons[i] << "\"";
  o << "], \"triangles\": " << p.bvh.NumberOfTriangles() << ", \"open_meshes\": " << p.open
    << ", \"radius\": " << p.radius << ", \"slices\": " << p.grid.slices
    << ", \"covered_pixels\": " << p.frame.covered << ", \"combined_pixels\": " << p.combined;
  if (!p.error.empty())
    o << ", \"error\": \"" << p.error << "\"";
  o << "}";
  return o.str();
}

void vtkContextualAOPass::Render(const vtkRenderState* s)
{
  Internals& p = *this->Internal;
  ++this->FrameCount;
  p.stages.clear();
  p.reasons.clear();
  p.ms.clear();
  p.error.clear();
  p.combined = 0;
  this->NumberOfRenderedProps = 0;
  if (this->DelegatePass)
  {
    this->DelegatePass->Render(s);
    this->NumberOfRenderedProps = this->DelegatePass->GetNumberOfRenderedProps();
  }
  vtkRenderer* ren = s->GetRenderer();
  if (this->Method == NONE || !ren)
    return;

  // The visible opaque polygonal actors, and what the grid depends on.
  std::vector<std::pair<vtkActor*, vtkPolyData*>> actors; // one entry per polygonal piece
  std::vector<double> sceneKey{ static_cast<double>(this->Slices), this->Radius };
  vtkActorCollection* collection = ren->GetActors();
  vtkCollectionSimpleIterator it;
  collection->InitTraversal(it);
  while (vtkActor* actor = collection->GetNextActor(it))
  {
    if (!actor->GetVisibility() || !actor->HasOpaqueGeometry())
      continue;
    for (vtkPolyData* data : Pieces(actor->GetMapper()))
    {
      actors.emplace_back(actor, data);
      sceneKey.push_back(static_cast<double>(reinterpret_cast<std::uintptr_t>(actor)));
      sceneKey.push_back(static_cast<double>(reinterpret_cast<std::uintptr_t>(data)));
      sceneKey.push_back(static_cast<double>(data->GetMTime()));
      vtkMatrix4x4* m = actor->GetMatrix();
      for (int i = 0; i < 16; ++i)
        sceneKey.push_back(m->GetElement(i / 4, i % 4));
    }
  }
  if (actors.empty())
  {
    p.frame = cao::SurfaceFrame();
    p.viewKey.clear();
    return; // no surfaces: no surface work
  }
  if (this->Slices < 32 || this->Slices > 1024 || this->Slices % 32 != 0)
  {
    p.error = "Slices must be 32..1024 and a multiple of 32";
    vtkErrorMacro(<< p.error << " (got " << this->Slices << ")");
    return;
  }

  // 1. The grid: only when the geometry, a pose or the grid settings changed.
  if (sceneKey != p.sceneKey)
  {
    const auto start = std::chrono::steady_clock::now();
    p.reasons.push_back(p.sceneKey.empty() ? "first frame" : "geometry or grid changed");
    p.points.clear();
    p.triangles.clear();
    std::vector<double> all;
    std::vector<std::int64_t> allTris;
    for (const auto& piece : actors)
    {
      std::vector<double> pts;
      std::vector<std::int64_t> tris;
      vtkCAO::TrianglesOf(piece.second, pts, tris);
      vtkMatrix4x4* m = piece.first->GetMatrix();
      for (std::size_t i = 0; i < pts.size(); i += 3)
      {
        const double in[4] = { pts[i], pts[i + 1], pts[i + 2], 1.0 };
        double out[4];
        m->MultiplyPoint(in, out);
        for (int d = 0; d < 3; ++d)
          pts[i + d] = out[d] / out[3];
      }
      const std::int64_t base = static_cast<std::int64_t>(all.size() / 3);
      all.insert(all.end(), pts.begin(), pts.end());
      for (std::int64_t id : tris)
        allTris.push_back(id + base);
      p.points.push_back(std::move(pts));
      p.triangles.push_back(std::move(tris));
    }
    std::string error;
    std::vector<cao::MeshView> views;
    for (std::size_t i = 0; i < p.points.size(); ++i)
      views.push_back({ &p.points[i], &p.triangles[i] });
    if (!p.bvh.Build(all, allTris, error) || p.bvh.NumberOfTriangles() == 0)
    {
      p.error = error.empty() ? "the actors have no triangle with an area" : error;
      vtkErrorMacro(<< "Cannot build the scene: " << p.error);
      p.sceneKey.clear();
      return;
    }
    const std::array<double, 6>& b = p.bvh.Bounds();
    const double diagonal = std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) +
      (b[5] - b[4]) * (b[5] - b[4]));
    p.radius = this->Radius > 0 ? this->Radius : 0.1 * diagonal;
    if (!cao::VoxelizeWorld(views, b, 1.05 * p.radius, this->Slices, p.grid, error))
    {
      p.error = error;
      vtkErrorMacro(<< "Cannot voxelize the scene: " << error);
      p.sceneKey.clear();
      return;
    }
    p.open = 0;
    for (std::int64_t e : p.grid.openEdges)
      p.open += e > 0;
    p.sceneKey = sceneKey;
    ++p.serial;
    ++this->VoxelizeCount;
    p.stages.push_back("voxelize");
    p.ms.push_back(Since(start));
  }

  // 2. The AO image: only when the grid, the camera, the viewport or the
  // AO settings changed.
  int width = 0, height = 0, x0 = 0, y0 = 0;
  ren->GetTiledSizeAndOrigin(&width, &height, &x0, &y0);
  vtkCamera* camera = ren->GetActiveCamera();
  const double aspect = width > 0 && height > 0 ? double(width) / height : 1.0;
  vtkMatrix4x4* toNDC = camera->GetCompositeProjectionTransformMatrix(aspect, -1, 1);
  std::vector<double> viewKey{ static_cast<double>(p.serial), static_cast<double>(width),
    static_cast<double>(height), static_cast<double>(x0), static_cast<double>(y0),
    static_cast<double>(this->Quality), p.radius };
  for (int i = 0; i < 16; ++i)
    viewKey.push_back(toNDC->GetElement(i / 4, i % 4));
  if (viewKey != p.viewKey)
  {
    auto start = std::chrono::steady_clock::now();
    p.reasons.push_back(p.stages.empty() ? "camera or settings changed" : "new grid");
    cao::PixelCamera pixels;
    vtkMatrix4x4::Invert(&toNDC->Element[0][0], pixels.ndcToWorld);
    pixels.width = width;
    pixels.height = height;
    std::string error;
    if (!cao::CastPrimary(p.bvh, pixels, p.frame, error))
    {
      p.error = error;
      vtkErrorMacro(<< error);
      p.viewKey.clear();
      return;
    }
    p.stages.push_back("primary");
    p.ms.push_back(Since(start));
    start = std::chrono::steady_clock::now();
    cao::VCTSettings settings;
    settings.quality = static_cast<cao::VCTQuality>(this->Quality);
    settings.slices = this->Slices;
    settings.radius = p.radius;
    cao::VCTPlan plan;
    if (!cao::BuildVCTPlan(settings, p.grid, plan, error) || !cao::VCTFrame(p.grid, plan, p.frame, 0, error))
    {
      p.error = error;
      vtkErrorMacro(<< error);
      p.viewKey.clear();
      return;
    }
    p.viewKey = viewKey;
    p.x0 = x0;
    p.y0 = y0;
    ++this->TraceCount;
    p.stages.push_back("trace");
    p.ms.push_back(Since(start));
  }

  // 3. Combine: every frame (the colours are the scene's own drawing).
  auto start = std::chrono::steady_clock::now();
  vtkRenderWindow* window = ren->GetRenderWindow();
  vtkNew<vtkFloatArray> rgba;
  window->GetRGBAPixelData(x0, y0, x0 + width - 1, y0 + height - 1, 0, rgba, 0);
  const std::size_t count = static_cast<std::size_t>(width) * height;
  if (static_cast<std::size_t>(rgba->GetNumberOfTuples()) != count)
  {
    p.error = "the frame could not be read back";
    vtkErrorMacro(<< p.error);
    return;
  }
  float* c = rgba->GetPointer(0);
  for (std::size_t i = 0; i < count; ++i)
  {
    const double a = p.frame.ao[i];
    if (!std::isfinite(a))
      continue;
    const float f = static_cast<float>(1.0 - this->Strength * (1.0 - std::min(1.0, std::max(0.0, a))));
    for (int k = 0; k < 3; ++k)
      c[4 * i + k] *= f;
    ++p.combined;
  }
  window->SetRGBAPixelData(x0, y0, x0 + width - 1, y0 + height - 1, rgba, 0, 0, 0);
  p.stages.push_back("combine");
  p.ms.push_back(Since(start));
}

void vtkContextualAOPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Method: " << this->Method << "\n"
     << indent << "Radius: " << this->Radius << "\n"
     << indent << "Strength: " << this->Strength << "\n"
     << indent << "Quality: " << this->Quality << "\n"
     << indent << "Slices: " << this->Slices << "\n"
     << indent << "DelegatePass: " << this->DelegatePass << "\n";
}
