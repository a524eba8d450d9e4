/**
 * pqCAOLinesInViewDecorator — the ParaView GUI shows a Contextual AO view's
 * line settings (Line AO Method, its samples, slices and shading) only while the
 * view draws lines: XML type "CAOLinesInView" in ContextualAOView.xml.
 *
 * After each render of the view it reads how many actors with lines the
 * view's pass saw (vtkPVRenderViewWithContextualAO::GetLineActorsInView:
 * the client's own view, and in a remote session after each still render
 * also the server's, gathered as vtkCAOLineActorsInformation; whichever
 * draws) and asks the panel to show or hide the widget when that crosses 0.
 */
#ifndef pqCAOLinesInViewDecorator_h
#define pqCAOLinesInViewDecorator_h

#include "pqPropertyWidgetDecorator.h"
#include "vtkWeakPointer.h" // For the view proxy

class vtkObject;
class vtkSMProxy;

class pqCAOLinesInViewDecorator : public pqPropertyWidgetDecorator
{
  Q_OBJECT
  typedef pqPropertyWidgetDecorator Superclass;

public:
  pqCAOLinesInViewDecorator(vtkPVXMLElement* xml, pqPropertyWidget* parent);
  ~pqCAOLinesInViewDecorator() override;

  /// Whether the view's last AO frame had actors with lines.
  bool canShowWidget(bool showAdvanced) const override;

private:
  Q_DISABLE_COPY(pqCAOLinesInViewDecorator)
  /// The view proxy's EndEvent (its call data: 1 after an interactive render).
  void rendered(vtkObject* caller, unsigned long event, void* callData);
  void update(bool still);
  vtkWeakPointer<vtkSMProxy> Proxy; ///< the view's (its widget may be gone first)
  unsigned long Observer = 0;
  bool Lines = false;
};

#endif
