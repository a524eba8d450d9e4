#include "pqCAOPointerTracker.h"

#include "pqApplicationCore.h"
#include "vtkContextualAOVolumeMapper.h"
#include "vtkSMCAOVolumeRepresentationProxy.h"

#include <QApplication>
#include <QEvent>
#include <QMouseEvent>
#include <QTimer>
#include <QWidget>

namespace
{
/// Whether a press delivered to `object` is over a render view: the VTK
/// widget (native or stereo) or the OpenGL window inside it.
bool InRenderView(QObject* object)
{
  for (QObject* o = object; o; o = o->parent())
    if (o->inherits("QVTKOpenGLNativeWidget") || o->inherits("QVTKOpenGLStereoWidget") ||
      o->inherits("QVTKOpenGLWindow") || o->inherits("pqQVTKWidget"))
      return true;
  return false;
}
}

pqCAOPointerTracker::pqCAOPointerTracker(QObject* parent)
  : Superclass(parent)
{
}

pqCAOPointerTracker::~pqCAOPointerTracker() = default;

void pqCAOPointerTracker::onStartup()
{
  if (qApp)
    qApp->installEventFilter(this);
}

void pqCAOPointerTracker::onShutdown()
{
  if (qApp)
    qApp->removeEventFilter(this);
  vtkContextualAOVolumeMapper::SetPointerHeld(false);
  for (const auto& proxy : this->Remote)
    proxy->PushPointerHeld(false);
  this->Remote.clear();
}

bool pqCAOPointerTracker::eventFilter(QObject* watched, QEvent* event)
{
  const QEvent::Type type = event->type();
  if ((type == QEvent::MouseButtonPress || type == QEvent::MouseButtonDblClick) &&
    !vtkContextualAOVolumeMapper::GetPointerHeld() && InRenderView(watched))
  {
    vtkContextualAOVolumeMapper::SetPointerHeld(true);
    // A GUI connected to a pvserver: the servers' mappers draw the frames.
    this->Remote.clear();
    for (vtkSMCAOVolumeRepresentationProxy* proxy :
      vtkSMCAOVolumeRepresentationProxy::ShownInRemoteSessions())
    {
      proxy->PushPointerHeld(true);
      this->Remote.emplace_back(proxy);
    }
  }
  else if (vtkContextualAOVolumeMapper::GetPointerHeld() &&
    (((type == QEvent::MouseButtonRelease || type == QEvent::MouseMove) &&
       static_cast<QMouseEvent*>(event)->buttons() == Qt::NoButton) ||
      type == QEvent::ApplicationDeactivate || type == QEvent::WindowBlocked))
  {
    // The release, or, should it have been lost (the application left, or
    // a modal dialog opened, while the button was held), a move with no
    // button held, the application's deactivation or a blocked window.
    vtkContextualAOVolumeMapper::SetPointerHeld(false);
    const bool remote = !this->Remote.empty();
    for (const auto& proxy : this->Remote)
      proxy->PushPointerHeld(false);
    this->Remote.clear();
    // Frames drawn while held were interactive: one still frame of every
    // view after the release, after the widget's own (queued). (A server's
    // count is not read back: a round trip per release; its still frame,
    // when nothing moved since the last one, redraws what it kept.)
    if (vtkContextualAOVolumeMapper::GetFramesDrawnWhileHeld() > 0 || remote)
      QTimer::singleShot(0, []() {
        if (pqApplicationCore* core = pqApplicationCore::instance())
          core->render();
      });
  }
  return Superclass::eventFilter(watched, event);
}
