/**
 * pqCAOLinesInViewDecorator — the ParaView GUI shows a Contextual AO view's
 * line settings (Line AO, its samples, slices and shading) only while the
 * view draws lines: XML type "CAOLinesInView" in ContextualAOView.xml.
 *
 * After each render of the view it reads how many actors with lines the
 * view's pass saw (vtkPVRenderViewWithContextualAO::GetLineActorsInView:
 * the client's own view, and in a remote session also the server's, the
 * information property LineActorsInView, whichever draws) and asks the
 * panel to show or hide the widget when that crosses 0.
 */
#ifndef pqCAOLinesInViewDecorator_h
#define pqCAOLinesInViewDecorator_h

#include "pqPropertyWidgetDecorator.h"

#include <QPointer>

class pqView;

class pqCAOLinesInViewDecorator : public pqPropertyWidgetDecorator
{
  Q_OBJECT
  typedef pqPropertyWidgetDecorator Superclass;

public:
  pqCAOLinesInViewDecorator(vtkPVXMLElement* xml, pqPropertyWidget* parent);
  ~pqCAOLinesInViewDecorator() override;

  /// Whether the view's last AO frame had actors with lines.
  bool canShowWidget(bool showAdvanced) const override;

private Q_SLOTS:
  void watch(pqView* view);
  void update();

private:
  Q_DISABLE_COPY(pqCAOLinesInViewDecorator)
  QPointer<pqView> View;
  bool Lines = false;
};

#endif
