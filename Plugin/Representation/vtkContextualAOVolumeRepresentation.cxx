#include "vtkContextualAOVolumeRepresentation.h"

#include "vtkActor.h"
#include "vtkAlgorithm.h"
#include "vtkCommand.h"
#include "vtkContextualAOVolumeMapper.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkPVLODVolume.h"
#include "vtkProcessModule.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkSmartPointer.h"
#include "vtkTransform.h"

#include "vtkCAOInput.h"
#include "vtkCellData.h"
#include "vtkDataObject.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkImageData.h"
#include "vtkPointData.h"

#include <algorithm>
#include <sstream>
#include <cmath>
#include <string>

vtkStandardNewMacro(vtkContextualAOVolumeRepresentation);

//------------------------------------------------------------------------------
vtkContextualAOVolumeRepresentation::vtkContextualAOVolumeRepresentation()
{
  // The project's mapper in place of the smart volume mapper; the
  // superclass feeds it the delivered data and the array to render.
  this->VolumeMapper = vtkSmartPointer<vtkContextualAOVolumeMapper>::New();
  this->Actor->SetMapper(this->VolumeMapper);
  this->ClipActor->SetMapper(this->ClipMapper);
  // The mapper's LAO precompute runs inside a render: its progress becomes
  // the representation's (ParaView shows a representation's progress in
  // the status bar and its Abort button sets the representation's
  // AbortExecute, handed back to the mapper here; a pvserver's processes
  // hand back the abort but keep the progress: ForwardProgress).
  this->VolumeMapper->AddObserver(vtkCommand::ProgressEvent, this,
    &vtkContextualAOVolumeRepresentation::ForwardProgress);
}

//------------------------------------------------------------------------------
void vtkContextualAOVolumeRepresentation::ForwardProgress(vtkObject*, unsigned long, void*)
{
  vtkContextualAOVolumeMapper* mapper = this->GetAOMapper();
  if (this->GetAbortExecute())
  {
    mapper->SetAbortExecute(1);
    this->SetAbortExecute(0);
  }
  // In a pvserver the progress reaches the GUI while it waits for the
  // frame's image, and the GUI's event loop then repaints the render view
  // in the middle of that render: VTK's cached OpenGL state no longer
  // matches the context ("Error in cache state" at every clip move on a
  // server of 2 processes). The GUI's own renders (a builtin session) and
  // pvbatch (every rank) keep it. The abort set on the representation
  // still reaches the mapper (above), though the GUI, seeing no progress,
  // shows no Abort button for that render.
  const int process = vtkProcessModule::GetProcessType();
  if (process == vtkProcessModule::PROCESS_SERVER ||
    process == vtkProcessModule::PROCESS_DATA_SERVER ||
    process == vtkProcessModule::PROCESS_RENDER_SERVER)
    return;
  this->SetProgressText("Contextual AO: LAO precompute");
  this->UpdateProgress(mapper->GetProgress());
}

//------------------------------------------------------------------------------
vtkContextualAOVolumeRepresentation::~vtkContextualAOVolumeRepresentation() = default;

//------------------------------------------------------------------------------
const char* vtkContextualAOVolumeRepresentation::GetFrameReport()
{
  vtkContextualAOVolumeMapper* mapper = this->GetAOMapper();
  this->FrameReport = mapper ? mapper->GetLastFrameReport() : std::string();
  return this->FrameReport.c_str();
}

void vtkContextualAOVolumeRepresentation::SetPointerHeld(int held)
{
  vtkContextualAOVolumeMapper::SetPointerHeld(held != 0);
}

//------------------------------------------------------------------------------
vtkContextualAOVolumeMapper* vtkContextualAOVolumeRepresentation::GetAOMapper()
{
  return vtkContextualAOVolumeMapper::SafeDownCast(this->VolumeMapper);
}

void vtkContextualAOVolumeRepresentation::SetAmbientOcclusion(bool on)
{
  this->GetAOMapper()->SetAmbientOcclusion(on);
}
void vtkContextualAOVolumeRepresentation::SetAOStrength(double s)
{
  this->GetAOMapper()->SetAOStrength(s);
}
void vtkContextualAOVolumeRepresentation::SetAOCalibration(int c)
{
  this->GetAOMapper()->SetAOCalibration(c);
}
void vtkContextualAOVolumeRepresentation::SetRayPattern(int p)
{
  this->GetAOMapper()->SetRayPattern(p);
}
void vtkContextualAOVolumeRepresentation::SetNumberOfRays(int n)
{
  this->GetAOMapper()->SetNumberOfRays(n);
}
void vtkContextualAOVolumeRepresentation::SetReach(double r)
{
  this->GetAOMapper()->SetReach(r);
}
void vtkContextualAOVolumeRepresentation::SetNumberOfSamples(int m)
{
  this->GetAOMapper()->SetNumberOfSamples(m);
}
void vtkContextualAOVolumeRepresentation::SetSampleDensity(double d)
{
  this->GetAOMapper()->SetSampleDensity(d);
}
void vtkContextualAOVolumeRepresentation::SetStartOffset(double o)
{
  this->GetAOMapper()->SetStartOffset(o);
}
void vtkContextualAOVolumeRepresentation::SetRayVariation(int v)
{
  this->GetAOMapper()->SetRayVariation(v);
}
void vtkContextualAOVolumeRepresentation::SetQuality(int p)
{
  this->GetAOMapper()->SetQuality(p);
}
void vtkContextualAOVolumeRepresentation::SetMode(int m)
{
  this->MeshesChanged = true; // meshes without their own mode follow it
  this->GetAOMapper()->SetMode(m);
}
void vtkContextualAOVolumeRepresentation::SetNumberOfClipLayers(int l)
{
  this->GetAOMapper()->SetNumberOfClipLayers(l);
}

//------------------------------------------------------------------------------
void vtkContextualAOVolumeRepresentation::UpdateMapperParameters()
{
  this->Superclass::UpdateMapperParameters();
  vtkContextualAOVolumeMapper* mapper = this->GetAOMapper();
  vtkImageData* data = vtkImageData::SafeDownCast(mapper->GetInputDataObject(0, 0));
  // vtkLocalAmbientOcclusion's output arrays (vtkCAO::AmbientOcclusionName,
  // vtkCAO::LAOSettingsName).
  const bool upstream = this->UseInputAmbientOcclusion && data &&
    data->GetPointData()->GetArray("AmbientOcclusion") &&
    data->GetFieldData()->GetAbstractArray("LAOSettings");
  mapper->SetAmbientOcclusionArrayName(upstream ? "AmbientOcclusion" : nullptr);
  this->WarnWithoutScalars(data);
  this->UpdateBuiltInShape(data);
  if (this->MeshesChanged)
  {
    mapper->RemoveAllClipShapes();
    for (std::size_t i = 0; i < this->MeshActors.size(); ++i)
    {
      const int mode = i < this->MeshModes.size() && this->MeshModes[i] >= 0
        ? this->MeshModes[i]
        : mapper->GetMode();
      mapper->AddClipShape(this->MeshActors[i], mode);
    }
    this->MeshesChanged = false;
  }
}

//------------------------------------------------------------------------------
void vtkContextualAOVolumeRepresentation::WarnWithoutScalars(vtkImageData* data)
{
  // A volume draws the array it is coloured by; without one nothing is
  // drawn. Said once per input (and again when the input changes), not at
  // every render.
  vtkInformation* info = this->GetInputArrayInformation(0);
  const char* name = info && info->Has(vtkDataObject::FIELD_NAME())
    ? info->Get(vtkDataObject::FIELD_NAME())
    : nullptr;
  if (!data || !this->GetVisibility() || (name && name[0]))
  {
    this->WarnedInputTime = 0;
    return;
  }
  if (this->WarnedInputTime == data->GetMTime())
    return;
  this->WarnedInputTime = data->GetMTime();
  if (data->GetPointData()->GetNumberOfArrays() == 0 && data->GetCellData()->GetNumberOfArrays() == 0)
    vtkWarningMacro("Contextual AO Volume draws nothing: the input has no point or cell arrays "
                    "(a volume is drawn from the scalars it is coloured by).");
  else
    vtkWarningMacro("Contextual AO Volume draws nothing while it is coloured by Solid Color: "
                    "colour it by a point or cell array (Coloring).");
}

//------------------------------------------------------------------------------
void vtkContextualAOVolumeRepresentation::AddClipMeshSource(vtkAlgorithm* source)
{
  if (!source)
    return;
  vtkNew<vtkPolyDataMapper> m;
  m->SetInputConnection(source->GetOutputPort(0));
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(m);
  this->MeshActors.push_back(actor);
  this->MeshesChanged = true;
  this->Modified();
}

void vtkContextualAOVolumeRepresentation::RemoveAllClipMeshSources()
{
  if (this->MeshActors.empty())
    return;
  this->MeshActors.clear();
  this->MeshesChanged = true;
  this->Modified();
}

void vtkContextualAOVolumeRepresentation::SetClipMeshMode(int index, int mode)
{
  // (the panel's "Clip Mesh Modes": one mode per clip mesh, in order)
  if (index < 0 || index >= vtkContextualAOVolumeMapper::MAX_CLIP_SHAPES)
  {
    vtkErrorMacro("Clip Mesh Modes: a volume takes at most "
      << vtkContextualAOVolumeMapper::MAX_CLIP_SHAPES << " clip meshes; mode " << index + 1
      << " is past them and is ignored.");
    return;
  }
  if (mode < -1 || mode > 1)
  {
    vtkErrorMacro("Clip Mesh Modes: the mode of clip mesh " << index + 1
      << " must be 0 (subtraction), 1 (probing) or -1 (as Clip Mode); got " << mode
      << ". That mesh carves with the Clip Mode instead.");
    mode = -1;
  }
  if (this->MeshModes.size() <= static_cast<std::size_t>(index))
    this->MeshModes.resize(index + 1, -1);
  this->MeshModes[index] = mode;
  this->MeshesChanged = true;
  this->Modified();
}

void vtkContextualAOVolumeRepresentation::RemoveAllClipMeshModes()
{
  if (this->MeshModes.empty())
    return;
  this->MeshModes.clear();
  this->MeshesChanged = true;
  this->Modified();
}

int vtkContextualAOVolumeRepresentation::GetNumberOfClipMeshSources() const
{
  return static_cast<int>(this->MeshActors.size());
}

//------------------------------------------------------------------------------
void vtkContextualAOVolumeRepresentation::SetClipScale(double x, double y, double z)
{
  // As given: a negative scale mirrors, as a prop's; a zero one is refused
  // when the shape is placed (UpdateBuiltInShape). (A floor of 1e-9 here
  // made the clip of a volume 1e-10 across cover all of it: the volume
  // vanished without a word.)
  const double scale[3] = { x, y, z };
  if (!std::equal(scale, scale + 3, this->ClipScale))
  {
    std::copy(scale, scale + 3, this->ClipScale);
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkContextualAOVolumeRepresentation::GetClipShapeMatrix(double matrix[16])
{
  // vtkPVBox's transform of the reference box, then the box's centre and
  // half-extents, so that the shape of half-extent 1 fills the box.
  const double unit[6] = { 0, 1, 0, 1, 0, 1 };
  const double* b = this->ClipUseReferenceBounds ? this->ClipReferenceBounds : unit;
  vtkNew<vtkTransform> t;
  t->Translate(this->ClipPosition);
  t->RotateZ(this->ClipOrientation[2]);
  t->RotateX(this->ClipOrientation[0]);
  t->RotateY(this->ClipOrientation[1]);
  t->Scale(this->ClipScale);
  t->Translate(0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]));
  t->Scale(0.5 * (b[1] - b[0]), 0.5 * (b[3] - b[2]), 0.5 * (b[5] - b[4]));
  if (this->ClipShape == PLANE)
  {
    // The plane of the box's -z face, the half-space that holds the box:
    // through the centre, at the default pose (the data's +z face) it
    // removed nothing, and picking Plane changed nothing on the screen.
    t->Translate(0.0, 0.0, -1.0);
  }
  vtkMatrix4x4::DeepCopy(matrix, t->GetMatrix());
}

//------------------------------------------------------------------------------
void vtkContextualAOVolumeRepresentation::UpdateBuiltInShape(vtkImageData* data)
{
  vtkContextualAOVolumeMapper* mapper = this->GetAOMapper();
  mapper->SetHostClipError(std::string());
  if (this->ClipShape == NONE)
  {
    this->LoggedClipError.clear();
    mapper->SetClipShape(nullptr);
    return;
  }
  const double* b = this->ClipReferenceBounds;
  const bool boundsOk = !this->ClipUseReferenceBounds ||
    (b[1] - b[0] > 0.0 && b[3] - b[2] > 0.0 && b[5] - b[4] > 0.0 &&
      std::all_of(b, b + 6, [](double v) { return std::isfinite(v); }));
  double matrix[16];
  this->GetClipShapeMatrix(matrix);
  const double* s = this->ClipScale;
  const bool scaleOk = std::all_of(s, s + 3, [](double v) { return std::isfinite(v) && v != 0.0; }) &&
    std::all_of(matrix, matrix + 16, [](double v) { return std::isfinite(v); });
  const double* p = this->ClipPosition;
  const double* r = this->ClipOrientation;
  const bool poseOk = std::all_of(p, p + 3, [](double v) { return std::isfinite(v); }) &&
    std::all_of(r, r + 3, [](double v) { return std::isfinite(v); });
  if (!poseOk || !boundsOk || !scaleOk)
  {
    // Said once in the log and in every frame's report while it holds.
    std::ostringstream why;
    if (!poseOk)
      why << "The clip box's Clip Position (" << p[0] << " " << p[1] << " " << p[2]
          << ") or Clip Rotation (" << r[0] << " " << r[1] << " " << r[2]
          << ") is not finite: nothing is clipped, the volume is drawn unclipped.";
    else
      why << "The clip box is empty or not finite (Clip Scale " << s[0] << " " << s[1] << " " << s[2]
          << ", each axis non-zero and finite; reference bounds " << b[0] << " " << b[1] << " " << b[2]
          << " " << b[3] << " " << b[4] << " " << b[5]
          << ", each max above its min): nothing is clipped, the volume is drawn unclipped.";
    // (this runs at every update of the representation: a GUI edit gave
    // the same error four times)
    if (why.str() != this->LoggedClipError)
      vtkErrorMacro(<< why.str());
    this->LoggedClipError = why.str();
    mapper->SetHostClipError(why.str());
    mapper->SetClipShape(nullptr);
    return;
  }
  this->LoggedClipError.clear();
  static const char* names[] = { "", "sphere", "cube", "torus", "plane" };
  // Half-extent 1: the torus' ring radius 3/4 (tube 1/4) reaches the box's
  // faces. A plane's slab must cover the data from the pose
  // (vtkCAO::PlaneSlabSize): it only grows, with room to spare, so that
  // dragging the plane does not remake the mesh (and its depth maps) at
  // every step.
  double size = this->ClipShape == TORUS ? 0.75 : 1.0;
  if (this->ClipShape == PLANE && data)
  {
    const double needed = vtkCAO::PlaneSlabSize(data, matrix);
    size = this->BuiltShape == PLANE && this->BuiltSize >= needed ? this->BuiltSize : 2.0 * needed;
  }
  if (this->ClipShape != this->BuiltShape || size != this->BuiltSize)
  {
    std::string error;
    vtkSmartPointer<vtkPolyData> mesh = vtkCAO::MakeShape(names[this->ClipShape], size, error);
    if (!mesh)
    {
      vtkErrorMacro("Cannot make the clip shape: " << error);
      mapper->SetClipShape(nullptr);
      return;
    }
    this->ClipMapper->SetInputData(mesh);
    this->BuiltShape = this->ClipShape;
    this->BuiltSize = size;
  }
  vtkNew<vtkMatrix4x4> m;
  m->DeepCopy(matrix);
  vtkMatrix4x4* current = this->ClipActor->GetUserMatrix();
  bool same = current != nullptr;
  for (int i = 0; same && i < 16; ++i)
  {
    same = current->GetElement(i / 4, i % 4) == matrix[i];
  }
  if (!same) // an unchanged pose keeps the actor's time: no "clip shapes moved"
  {
    this->ClipActor->SetUserMatrix(m);
  }
  mapper->SetClipShape(this->ClipActor);
}

//------------------------------------------------------------------------------
void vtkContextualAOVolumeRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "UseInputAmbientOcclusion: " << this->UseInputAmbientOcclusion << "\n";
  os << indent << "ClipShape: " << this->ClipShape << "\n";
  os << indent << "ClipPosition: " << this->ClipPosition[0] << " " << this->ClipPosition[1] << " "
     << this->ClipPosition[2] << "\n";
  os << indent << "ClipOrientation: " << this->ClipOrientation[0] << " "
     << this->ClipOrientation[1] << " " << this->ClipOrientation[2] << "\n";
  os << indent << "ClipScale: " << this->ClipScale[0] << " " << this->ClipScale[1] << " "
     << this->ClipScale[2] << "\n";
  os << indent << "ClipReferenceBounds:";
  for (double v : this->ClipReferenceBounds)
  {
    os << " " << v;
  }
  os << "\n" << indent << "ClipUseReferenceBounds: " << this->ClipUseReferenceBounds << "\n";
  os << indent << "AOMapper: " << this->VolumeMapper << "\n";
}
