/**
 * pqCAOPointerTracker — tells the contextual-AO volume mapper when a mouse
 * button is held over a render view (vtkContextualAOVolumeMapper::
 * SetPointerHeld), so that the still frames ParaView asks for during a
 * widget drag are drawn as interactive ones (InteractiveWhileDragging).
 *
 * The application's mouse events are watched (an event filter on the
 * application): a VTK interactor cannot tell, since a dragged widget takes
 * the interactor's focus and the release then reaches only the widget.
 * After the release, if the mapper drew frames while the button was held,
 * every view is rendered once more (still), so that the view ends exact.
 * When the GUI is connected to a pvserver, the servers' processes draw:
 * the press and the release are also sent to them (one "Contextual AO
 * Volume" representation per server, PushPointerHeld), and every view is
 * rendered once after the release.
 * Started with the GUI (an auto-start interface); pvpython, pvbatch and
 * the server do not load it.
 */
#ifndef pqCAOPointerTracker_h
#define pqCAOPointerTracker_h

#include <QObject>

#include "vtkSmartPointer.h"

#include <vector>

class vtkSMCAOVolumeRepresentationProxy;

class pqCAOPointerTracker : public QObject
{
  Q_OBJECT
  typedef QObject Superclass;

public:
  pqCAOPointerTracker(QObject* parent = nullptr);
  ~pqCAOPointerTracker() override;

  void onStartup();
  void onShutdown();

protected:
  bool eventFilter(QObject* watched, QEvent* event) override;

  /// The remote servers' representations told that the pointer is held
  /// (vtkSMCAOVolumeRepresentationProxy::PushPointerHeld), to be told of the
  /// release: held until then, so that a representation deleted during the
  /// drag still carries the release to its server (else every still frame
  /// there would stay interactive).
  std::vector<vtkSmartPointer<vtkSMCAOVolumeRepresentationProxy>> Remote;
};

#endif
