#include "vtkCAOFrameReportInformation.h"

#include "vtkClientServerStream.h"
#include "vtkContextualAOVolumeRepresentation.h"
#include "vtkObjectFactory.h"

vtkStandardNewMacro(vtkCAOFrameReportInformation);

vtkCAOFrameReportInformation::vtkCAOFrameReportInformation()
{
  this->RootOnly = 1;
}

void vtkCAOFrameReportInformation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Report: " << this->Report << "\n";
}

void vtkCAOFrameReportInformation::CopyFromObject(vtkObject* object)
{
  auto* representation = vtkContextualAOVolumeRepresentation::SafeDownCast(object);
  this->Report = representation ? representation->GetFrameReport() : "";
}

void vtkCAOFrameReportInformation::AddInformation(vtkPVInformation* other)
{
  auto* report = vtkCAOFrameReportInformation::SafeDownCast(other);
  if (report && this->Report.empty())
    this->Report = report->Report;
}

void vtkCAOFrameReportInformation::CopyToStream(vtkClientServerStream* stream)
{
  stream->Reset();
  *stream << vtkClientServerStream::Reply << this->Report.c_str() << vtkClientServerStream::End;
}

void vtkCAOFrameReportInformation::CopyFromStream(const vtkClientServerStream* stream)
{
  const char* report = nullptr;
  this->Report = stream->GetArgument(0, 0, &report) && report ? report : "";
}
