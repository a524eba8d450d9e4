/**
 * vtkCAOLineActorsInformation — how many actors with lines the Contextual
 * AO view's pass saw in its last AO frame
 * (vtkPVRenderViewWithContextualAO::GetLineActorsInView), gathered from
 * the processes that render (the most any holds). The GUI's line-settings
 * decorator gathers it in a remote session, where the view's information
 * properties would be read from the client's own view, which draws none of
 * the server's data.
 */
#ifndef vtkCAOLineActorsInformation_h
#define vtkCAOLineActorsInformation_h

#include "caoParaViewRepresentationModule.h" // For export macro
#include "vtkPVInformation.h"

class CAOPARAVIEWREPRESENTATION_EXPORT vtkCAOLineActorsInformation : public vtkPVInformation
{
public:
  static vtkCAOLineActorsInformation* New();
  vtkTypeMacro(vtkCAOLineActorsInformation, vtkPVInformation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// From a vtkPVRenderViewWithContextualAO (else 0).
  void CopyFromObject(vtkObject* object) override;
  /// The most of the two.
  void AddInformation(vtkPVInformation* other) override;
  void CopyToStream(vtkClientServerStream* stream) override;
  void CopyFromStream(const vtkClientServerStream* stream) override;

  vtkGetMacro(LineActors, int);

protected:
  vtkCAOLineActorsInformation() = default;
  ~vtkCAOLineActorsInformation() override = default;

private:
  vtkCAOLineActorsInformation(const vtkCAOLineActorsInformation&) = delete;
  void operator=(const vtkCAOLineActorsInformation&) = delete;
  int LineActors = 0;
};

#endif
