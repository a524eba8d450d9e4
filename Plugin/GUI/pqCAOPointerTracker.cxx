#include "pqCAOPointerTracker.h"

#include "pqApplicationCore.h"
#include "vtkContextualAOVolumeMapper.h"

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
}

bool pqCAOPointerTracker::eventFilter(QObject* watched, QEvent* event)
{
  const QEvent::Type type = event->type();
  if ((type == QEvent::MouseButtonPress || type == QEvent::MouseButtonDblClick) &&
    !vtkContextualAOVolumeMapper::GetPointerHeld() && InRenderView(watched))
  {
    vtkContextualAOVolumeMapper::SetPointerHeld(true);
  }
  else if (type == QEvent::MouseButtonRelease && vtkContextualAOVolumeMapper::GetPointerHeld() &&
    static_cast<QMouseEvent*>(event)->buttons() == Qt::NoButton)
  {
    vtkContextualAOVolumeMapper::SetPointerHeld(false);
    // Frames drawn while held were interactive: one still frame of every
    // view after the release, after the widget's own (queued).
    if (vtkContextualAOVolumeMapper::GetFramesDrawnWhileHeld() > 0)
      QTimer::singleShot(0, []() {
        if (pqApplicationCore* core = pqApplicationCore::instance())
          core->render();
      });
  }
  return Superclass::eventFilter(watched, event);
}
