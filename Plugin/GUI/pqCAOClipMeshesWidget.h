/**
 * pqCAOClipMeshesWidget — the Properties panel's "Clip meshes from the
 * pipeline" group (XML panel_widget "CAOClipMeshes" in
 * ContextualAORepresentation.xml): one row per polygonal source in the
 * pipeline, with a tick (it clips the volume) and its own named mode (As
 * Clip Mode, Subtraction, Probing).
 *
 * It edits two properties of the representation together: Clip Meshes (the
 * ticked sources, kept in the order they were ticked) and Clip Mesh Modes
 * (their modes, in the same order: -1 as Clip Mode, 0 subtraction, 1
 * probing). A change from Python, undo or a state file redraws the rows; a
 * source added, renamed, applied or deleted in the pipeline too.
 */
#ifndef pqCAOClipMeshesWidget_h
#define pqCAOClipMeshesWidget_h

#include "pqPropertyWidget.h"

#include "vtkWeakPointer.h" // For the rows' sources

#include <QPointer>

#include <vector>

class QComboBox;
class QLabel;
class QScrollArea;
class QTableWidget;
class vtkSMPropertyGroup;

class pqCAOClipMeshesWidget : public pqPropertyWidget
{
  Q_OBJECT
  typedef pqPropertyWidget Superclass;

public:
  pqCAOClipMeshesWidget(vtkSMProxy* proxy, vtkSMPropertyGroup* group, QWidget* parent = nullptr);
  ~pqCAOClipMeshesWidget() override;

  /// Writes the rows to Clip Meshes and Clip Mesh Modes.
  void apply() override;
  /// Rows from the properties again.
  void reset() override;

protected:
  /// Fits the rows to the panel's visible width (below).
  void showEvent(QShowEvent* event) override;
  bool eventFilter(QObject* watched, QEvent* event) override;

private Q_SLOTS:
  /// The rows made again from the pipeline and the properties.
  void refresh();
  /// A tick or a mode changed by the user.
  void edited();

private:
  Q_DISABLE_COPY(pqCAOClipMeshesWidget)
  /// The rows as the user left them: the sources to clip with, in order, and their modes.
  void rowsToLists(std::vector<vtkSMProxy*>& meshes, std::vector<int>& modes) const;

  /// At most as wide as the panel shows: ParaView's own colour editor
  /// makes the panel's contents wider than its default dock, and a row's
  /// mode, at the right, was then scrolled out of sight.
  void fitToPanel();

  QTableWidget* Table;
  QPointer<QScrollArea> Panel; ///< the Properties panel's scroll area
  QLabel* Note;
  std::vector<vtkWeakPointer<vtkSMProxy>> Sources; ///< one per row
  std::vector<vtkWeakPointer<vtkSMProxy>> Order;   ///< the ticked sources, in the order they clip
  std::vector<int> OrderModes;                     ///< their modes when read (for a source without a row)
  unsigned long Observers[2] = { 0, 0 };
  bool Refreshing = false;
  bool Applying = false;
};

#endif
