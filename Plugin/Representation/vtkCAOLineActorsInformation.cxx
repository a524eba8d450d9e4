#include "vtkCAOLineActorsInformation.h"

#include "vtkClientServerStream.h"
#include "vtkObjectFactory.h"
#include "vtkPVRenderViewWithContextualAO.h"

#include <algorithm>

vtkStandardNewMacro(vtkCAOLineActorsInformation);

void vtkCAOLineActorsInformation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "LineActors: " << this->LineActors << "\n";
}

void vtkCAOLineActorsInformation::CopyFromObject(vtkObject* object)
{
  auto* view = vtkPVRenderViewWithContextualAO::SafeDownCast(object);
  this->LineActors = view ? view->GetLineActorsInView() : 0;
}

void vtkCAOLineActorsInformation::AddInformation(vtkPVInformation* other)
{
  if (auto* lines = vtkCAOLineActorsInformation::SafeDownCast(other))
    this->LineActors = std::max(this->LineActors, lines->LineActors);
}

void vtkCAOLineActorsInformation::CopyToStream(vtkClientServerStream* stream)
{
  stream->Reset();
  *stream << vtkClientServerStream::Reply << this->LineActors << vtkClientServerStream::End;
}

void vtkCAOLineActorsInformation::CopyFromStream(const vtkClientServerStream* stream)
{
  int actors = 0;
  this->LineActors = stream->GetArgument(0, 0, &actors) ? actors : 0;
}
