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
 *
 * Clip Meshes keeps the display when a mesh is deleted. ParaView deletes
 * every representation that consumes a deleted source (its own displays
 * consume it through Input), and a proxy property makes its proxy a
 * consumer: deleting a ticked clip mesh deleted the whole volume display.
 * So the clip meshes' consumer is a relay (an internal proxy that is no
 * representation) which passes their changes on to this proxy, as the
 * consumer link did (an upstream edit re-carves); and when a clip mesh is
 * unregistered from the pipeline it is taken out of Clip Meshes (and its
 * mode out of Clip Mesh Modes).
 */
#ifndef vtkSMCAOVolumeRepresentationProxy_h
#define vtkSMCAOVolumeRepresentationProxy_h

#include "caoParaViewRepresentationModule.h" // For export macro
#include "vtkSMRepresentationProxy.h"
#include "vtkSmartPointer.h" // For the clip meshes' relay
#include "vtkWeakPointer.h"  // For the watched property

#include <vector> // For ShownInRemoteSessions

class vtkSMProperty;
class vtkSMSessionProxyManager;

class CAOPARAVIEWREPRESENTATION_EXPORT vtkSMCAOVolumeRepresentationProxy
  : public vtkSMRepresentationProxy
{
public:
  static vtkSMCAOVolumeRepresentationProxy* New();
  vtkTypeMacro(vtkSMCAOVolumeRepresentationProxy, vtkSMRepresentationProxy);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The representation type's name, as the XML gives it.
  static const char* TypeName() { return "Contextual AO Volume"; }

  /**
   * Tell the processes that draw this representation whether the
   * application's pointer button is held over a render view
   * (vtkContextualAOVolumeRepresentation::SetPointerHeld: the mapper's
   * process-wide flag, so that still frames asked for during a widget drag
   * are drawn as interactive ones). The GUI's pointer tracker calls it when
   * connected to a pvserver: the flag it sets in its own process does not
   * reach the server's. A method call, not a property: no undo entry, no
   * state. Nothing before the proxy's objects exist, nor once its session
   * is closed or lost.
   */
  void PushPointerHeld(bool held);

  /// The proxies of this class whose display is "Contextual AO Volume" in
  /// a session connected to a server (not builtin): one per session.
  static std::vector<vtkSMCAOVolumeRepresentationProxy*> ShownInRemoteSessions();

  /// A clip mesh (or a proxy upstream of it) changed: the relay's call, as
  /// a consumer's MarkDirtyFromProducer.
  void ClipMeshModified(vtkSMProxy* modifiedProxy, vtkSMProxy* producer, vtkSMProperty* property);

protected:
  vtkSMCAOVolumeRepresentationProxy();
  ~vtkSMCAOVolumeRepresentationProxy() override;

  void CreateVTKObjects() override;
  /// FrameReport in a remote session: gathered from the server's first
  /// process (the property itself would read the client's representation,
  /// which draws none of the server's data).
  void UpdatePropertyInformationInternal(vtkSMProperty* property = nullptr) override;
  /// The parent's Representation changed: colour by an array if it is ours
  /// and nothing is coloured.
  void RepresentationChanged();
  /// A property's value changed (ClipMeshes: the relay links made again).
  void SetPropertyModifiedFlag(const char* name, int flag) override;
  /// The clip meshes consumed by the relay instead of this proxy.
  void RelinkClipMeshes();
  /// The proxy manager's UnRegisterEvent: a deleted clip mesh leaves Clip Meshes.
  void ProxyUnRegistered(vtkObject* caller, unsigned long event, void* callData);

  vtkWeakPointer<vtkSMProperty> Watched; ///< the parent's Representation
  unsigned long Observer = 0;
  bool Choosing = false; ///< inside RepresentationChanged (no re-entry)
  vtkSmartPointer<vtkSMProxy> ClipMeshRelay;               ///< the clip meshes' consumer
  std::vector<vtkWeakPointer<vtkSMProxy>> RelayedMeshes;   ///< the meshes it consumes
  vtkWeakPointer<vtkSMSessionProxyManager> WatchedManager; ///< for UnRegisterEvent
  unsigned long ManagerObserver = 0;

private:
  vtkSMCAOVolumeRepresentationProxy(const vtkSMCAOVolumeRepresentationProxy&) = delete;
  void operator=(const vtkSMCAOVolumeRepresentationProxy&) = delete;
};

#endif
