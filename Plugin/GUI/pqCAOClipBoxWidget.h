/**
 * pqCAOClipBoxWidget — the Properties panel's "Clip shape pose (the box
 * widget)" group (XML panel_widget "CAOClipBox" in
 * ContextualAORepresentation.xml): ParaView's box widget (Position,
 * Rotation, Scale, the 3D box in the render view) without its reference
 * bounds' fields.
 *
 * The representation poses its shapes in the reference box [-1,1]^3, so
 * that Clip Position is the shape's centre and Clip Scale its half-extents;
 * ParaView's own InteractiveBox shows the six reference bounds and their
 * tick to every user, where the XML's panel_visibility cannot hide them
 * (the widget shows them whenever its group holds the two properties). The
 * properties stay in the group, so Reset Using Data Bounds still fits the
 * box to the data; Python and state files set them as before.
 */
#ifndef pqCAOClipBoxWidget_h
#define pqCAOClipBoxWidget_h

#include "pqBoxPropertyWidget.h"

class pqCAOClipBoxWidget : public pqBoxPropertyWidget
{
  Q_OBJECT
  typedef pqBoxPropertyWidget Superclass;

public:
  pqCAOClipBoxWidget(vtkSMProxy* proxy, vtkSMPropertyGroup* group, QWidget* parent = nullptr);
  ~pqCAOClipBoxWidget() override;

private:
  Q_DISABLE_COPY(pqCAOClipBoxWidget)
};

#endif
