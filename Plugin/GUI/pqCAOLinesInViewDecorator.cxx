#include "pqCAOLinesInViewDecorator.h"

#include "vtkPVRenderViewWithContextualAO.h"

#include "pqApplicationCore.h"
#include "pqPropertyWidget.h"
#include "pqServer.h"
#include "pqServerManagerModel.h"
#include "pqView.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxy.h"

#include <algorithm>

pqCAOLinesInViewDecorator::pqCAOLinesInViewDecorator(vtkPVXMLElement* xml, pqPropertyWidget* parent)
  : Superclass(xml, parent)
{
  pqServerManagerModel* model = pqApplicationCore::instance()->getServerManagerModel();
  if (pqView* view = model->findItem<pqView*>(parent->proxy()))
    this->watch(view);
  else // (a panel made before its view is registered)
    this->connect(model, &pqServerManagerModel::viewAdded, this, &pqCAOLinesInViewDecorator::watch);
  this->update();
}

pqCAOLinesInViewDecorator::~pqCAOLinesInViewDecorator() = default;

void pqCAOLinesInViewDecorator::watch(pqView* view)
{
  if (this->View || !view || view->getProxy() != this->parentWidget()->proxy())
    return;
  this->View = view;
  this->connect(view, &pqView::endRender, this, &pqCAOLinesInViewDecorator::update);
  this->update();
}

void pqCAOLinesInViewDecorator::update()
{
  vtkSMProxy* proxy = this->parentWidget()->proxy();
  int actors = 0;
  // The client's view (the only one in a built-in session; in a remote
  // one it draws what is delivered to the client).
  if (auto* view = vtkPVRenderViewWithContextualAO::SafeDownCast(proxy->GetClientSideObject()))
    actors = view->GetLineActorsInView();
  // The server's (remote rendering): its first process's count, which the
  // pass has made the most any process holds.
  if (this->View && this->View->getServer() && this->View->getServer()->isRemote() &&
    proxy->GetProperty("LineActorsInView"))
  {
    proxy->UpdatePropertyInformation(proxy->GetProperty("LineActorsInView"));
    actors = std::max(actors, vtkSMPropertyHelper(proxy, "LineActorsInView").GetAsInt());
  }
  const bool lines = actors > 0;
  if (lines != this->Lines)
  {
    this->Lines = lines;
    Q_EMIT this->visibilityChanged();
  }
}

bool pqCAOLinesInViewDecorator::canShowWidget(bool showAdvanced) const
{
  Q_UNUSED(showAdvanced);
  return this->Lines;
}
