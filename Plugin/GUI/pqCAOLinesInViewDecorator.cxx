#include "pqCAOLinesInViewDecorator.h"

#include "vtkCAOLineActorsInformation.h"
#include "vtkPVRenderViewWithContextualAO.h"

#include "pqPropertyWidget.h"
#include "vtkCommand.h"
#include "vtkNew.h"
#include "vtkPVSession.h"
#include "vtkSMProxy.h"
#include "vtkSMSession.h"

#include <algorithm>

pqCAOLinesInViewDecorator::pqCAOLinesInViewDecorator(vtkPVXMLElement* xml, pqPropertyWidget* parent)
  : Superclass(xml, parent)
  , Proxy(parent->proxy())
{
  if (this->Proxy)
    this->Observer = this->Proxy->AddObserver(vtkCommand::EndEvent, this, &pqCAOLinesInViewDecorator::rendered);
  this->update(true);
}

pqCAOLinesInViewDecorator::~pqCAOLinesInViewDecorator()
{
  if (this->Proxy)
    this->Proxy->RemoveObserver(this->Observer);
}

void pqCAOLinesInViewDecorator::rendered(vtkObject*, unsigned long, void* callData)
{
  const bool interactive = callData && *static_cast<int*>(callData) == 1;
  this->update(!interactive);
}

void pqCAOLinesInViewDecorator::update(bool still)
{
  vtkSMProxy* proxy = this->Proxy;
  if (!proxy)
    return;
  int actors = 0;
  // The client's view (the only one in a built-in session; in a remote
  // one it draws what is delivered to the client).
  if (auto* view = vtkPVRenderViewWithContextualAO::SafeDownCast(proxy->GetClientSideObject()))
    actors = view->GetLineActorsInView();
  // The server's (remote rendering), gathered from its processes after a
  // still render (a round trip; an information property would be read
  // from the client's view). The gather's result is not looked at: ParaView
  // 5.11's client session returned false here after filling it.
  if (still && proxy->GetSession() && proxy->GetSession()->IsA("vtkSMSessionClient"))
  {
    vtkNew<vtkCAOLineActorsInformation> information;
    proxy->GatherInformation(information, vtkPVSession::RENDER_SERVER);
    actors = std::max(actors, information->GetLineActors());
  }
  else if (!still)
    actors = std::max(actors, this->Lines ? 1 : 0); // (a drag keeps what the last still render said)
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
