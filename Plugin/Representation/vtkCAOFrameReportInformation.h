/**
 * vtkCAOFrameReportInformation — the volume mapper's report of the last
 * frame a "Contextual AO Volume" representation drew
 * (vtkContextualAOVolumeRepresentation::GetFrameReport), gathered from the
 * first process that renders. vtkSMCAOVolumeRepresentationProxy gathers it
 * for the FrameReport information property in a remote session, where the
 * property would be read from the client's own representation, which draws
 * none of the server's data.
 */
#ifndef vtkCAOFrameReportInformation_h
#define vtkCAOFrameReportInformation_h

#include "caoParaViewRepresentationModule.h" // For export macro
#include "vtkPVInformation.h"

#include <string> // For the report

class CAOPARAVIEWREPRESENTATION_EXPORT vtkCAOFrameReportInformation : public vtkPVInformation
{
public:
  static vtkCAOFrameReportInformation* New();
  vtkTypeMacro(vtkCAOFrameReportInformation, vtkPVInformation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// From a vtkContextualAOVolumeRepresentation (else empty).
  void CopyFromObject(vtkObject* object) override;
  /// The first non-empty report (the root's: the information is root only).
  void AddInformation(vtkPVInformation* other) override;
  void CopyToStream(vtkClientServerStream* stream) override;
  void CopyFromStream(const vtkClientServerStream* stream) override;

  const char* GetReport() const { return this->Report.c_str(); }

protected:
  vtkCAOFrameReportInformation();
  ~vtkCAOFrameReportInformation() override = default;

private:
  vtkCAOFrameReportInformation(const vtkCAOFrameReportInformation&) = delete;
  void operator=(const vtkCAOFrameReportInformation&) = delete;
  std::string Report;
};

#endif
