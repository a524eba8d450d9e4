/**
 * @class   vtkSMCAOVolumeRepresentationProxy
 * @brief   The "Contextual AO Volume" representation's proxy: choosing it
 *          colours by an array, as choosing ParaView's Volume does.
 *
 * ParaView picks a colour array when the representation type becomes
 * "Volume" or "Slice" and nothing is coloured yet (vtkSMPVRepresentationProxy
 * names those types); for any other type the display stays "Solid Color",
 * which a volume cannot draw. This sub-proxy watches its parent's
 * Representation property and, when it becomes "Contextual AO Volume" with
 * no scalar colouring, colours by the first point array (else the first
 * array) of the Coloring list and fits its maps to the data range, as
 * ParaView does for its own Volume. A colouring the user or a state file
 * chose is kept. Client-side glue only (server manager, no Qt).
 */
#ifndef vtkSMCAOVolumeRepresentationProxy_h
#define vtkSMCAOVolumeRepresentationProxy_h

#include "caoParaViewRepresentationModule.h" // For export macro
#include "vtkSMRepresentationProxy.h"
#include "vtkWeakPointer.h" // For the watched property

class vtkSMProperty;

class CAOPARAVIEWREPRESENTATION_EXPORT vtkSMCAOVolumeRepresentationProxy
  : public vtkSMRepresentationProxy
{
public:
  static vtkSMCAOVolumeRepresentationProxy* New();
  vtkTypeMacro(vtkSMCAOVolumeRepresentationProxy, vtkSMRepresentationProxy);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The representation type's name, as the XML gives it.
  static const char* TypeName() { return "Contextual AO Volume"; }

protected:
  vtkSMCAOVolumeRepresentationProxy();
  ~vtkSMCAOVolumeRepresentationProxy() override;

  void CreateVTKObjects() override;
  /// The parent's Representation changed: colour by an array if it is ours
  /// and nothing is coloured.
  void RepresentationChanged();

  vtkWeakPointer<vtkSMProperty> Watched; ///< the parent's Representation
  unsigned long Observer = 0;
  bool Choosing = false; ///< inside RepresentationChanged (no re-entry)

private:
  vtkSMCAOVolumeRepresentationProxy(const vtkSMCAOVolumeRepresentationProxy&) = delete;
  void operator=(const vtkSMCAOVolumeRepresentationProxy&) = delete;
};

#endif
