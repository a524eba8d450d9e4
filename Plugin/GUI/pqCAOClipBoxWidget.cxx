#include "pqCAOClipBoxWidget.h"

pqCAOClipBoxWidget::pqCAOClipBoxWidget(
  vtkSMProxy* proxy, vtkSMPropertyGroup* group, QWidget* parent)
  : Superclass(proxy, group, parent, /*hideReferenceBounds=*/true)
{
}

pqCAOClipBoxWidget::~pqCAOClipBoxWidget() = default;
