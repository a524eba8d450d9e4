#include "pqCAOClipMeshesWidget.h"

#include "pqApplicationCore.h"
#include "pqPipelineSource.h"
#include "pqServerManagerModel.h"
#include "pqUndoStack.h"
#include "vtkCommand.h"
#include "vtkSMDataTypeDomain.h"
#include "vtkSMIntVectorProperty.h"
#include "vtkSMPropertyGroup.h"
#include "vtkSMProxy.h"
#include "vtkSMProxyProperty.h"
#include "vtkSMSourceProxy.h"

#include <QComboBox>
#include <QFrame>
#include <QHeaderView>
#include <QEvent>
#include <QLabel>
#include <QScrollArea>
#include <QTableWidget>
#include <QVBoxLayout>

#include <algorithm>

namespace
{
const char* const MeshesName = "ClipMeshes";
const char* const ModesName = "ClipMeshModes";
// The combo's entries, index = mode + 1 (the representation's -1, 0, 1).
const char* const ModeNames[] = { "As Clip Mode", "Subtraction", "Probing" };

template <typename T>
std::ptrdiff_t IndexOf(const std::vector<vtkWeakPointer<vtkSMProxy>>& list, T* proxy)
{
  const auto at = std::find(list.begin(), list.end(), proxy);
  return at == list.end() ? -1 : at - list.begin();
}
}

pqCAOClipMeshesWidget::pqCAOClipMeshesWidget(vtkSMProxy* proxy, vtkSMPropertyGroup* group, QWidget* parent)
  : Superclass(proxy, parent)
{
  Q_UNUSED(group);
  this->setObjectName("CAOClipMeshes");
  this->setShowLabel(false);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  // The group's title, as ParaView draws one over its own groups (it draws
  // none over a custom group widget).
  auto* title = new QLabel("<b>Clip meshes from the pipeline</b>", this);
  title->setObjectName("ClipMeshesTitle");
  layout->addWidget(title);
  auto* rule = new QFrame(this);
  rule->setFrameShape(QFrame::HLine);
  rule->setFrameShadow(QFrame::Sunken);
  layout->addWidget(rule);
  this->Table = new QTableWidget(0, 2, this);
  this->Table->setObjectName("ClipMeshesTable");
  this->Table->setHorizontalHeaderLabels({ "Clip with", "Mode" });
  this->Table->verticalHeader()->hide();
  this->Table->horizontalHeader()->setSectionResizeMode(0, QHeaderView::Stretch);
  this->Table->horizontalHeader()->setSectionResizeMode(1, QHeaderView::ResizeToContents);
  this->Table->setSelectionMode(QAbstractItemView::NoSelection);
  // As wide as the panel (however narrow), as tall as its rows.
  this->Table->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Fixed);
  this->Table->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  this->Table->setVerticalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  this->Table->setToolTip("Tick a polygonal source of the pipeline to clip the volume with it "
                          "(a closed mesh, in its own coordinates, beside Clip Shape; at most 32 shapes). "
                          "Mode: Subtraction removes what lies inside the mesh, Probing keeps only it, "
                          "As Clip Mode follows Clip Mode.");
  layout->addWidget(this->Table);
  this->Note = new QLabel(this);
  this->Note->setObjectName("ClipMeshesNote");
  this->Note->setWordWrap(true);
  layout->addWidget(this->Note);
  QObject::connect(this->Table, &QTableWidget::itemChanged, this, &pqCAOClipMeshesWidget::edited);

  // A change from Python, undo or a state file shows in the rows.
  const char* names[2] = { MeshesName, ModesName };
  for (int i = 0; i < 2; ++i)
    if (vtkSMProperty* property = proxy ? proxy->GetProperty(names[i]) : nullptr)
      this->Observers[i] = property->AddObserver(vtkCommand::ModifiedEvent, this, &pqCAOClipMeshesWidget::refresh);
  // Sources come, go, are renamed or applied (their output's type known):
  // the rows again once the model has settled (queued).
  auto* model = pqApplicationCore::instance()->getServerManagerModel();
  QObject::connect(model, &pqServerManagerModel::sourceAdded, this, &pqCAOClipMeshesWidget::refresh, Qt::QueuedConnection);
  QObject::connect(model, &pqServerManagerModel::sourceRemoved, this, &pqCAOClipMeshesWidget::refresh, Qt::QueuedConnection);
  QObject::connect(model, &pqServerManagerModel::nameChanged, this, &pqCAOClipMeshesWidget::refresh, Qt::QueuedConnection);
  QObject::connect(model, &pqServerManagerModel::modifiedStateChanged, this, &pqCAOClipMeshesWidget::refresh,
    Qt::QueuedConnection);
  this->refresh();
}

pqCAOClipMeshesWidget::~pqCAOClipMeshesWidget()
{
  const char* names[2] = { MeshesName, ModesName };
  for (int i = 0; i < 2; ++i)
    if (vtkSMProperty* property = this->proxy() ? this->proxy()->GetProperty(names[i]) : nullptr)
      property->RemoveObserver(this->Observers[i]);
}

void pqCAOClipMeshesWidget::refresh()
{
  vtkSMProxy* proxy = this->proxy();
  auto* meshes = proxy ? vtkSMProxyProperty::SafeDownCast(proxy->GetProperty(MeshesName)) : nullptr;
  auto* modes = proxy ? vtkSMIntVectorProperty::SafeDownCast(proxy->GetProperty(ModesName)) : nullptr;
  if (!meshes || !modes || this->Applying)
    return;
  this->Refreshing = true;
  this->Order.clear();
  this->OrderModes.clear();
  for (unsigned int i = 0; i < meshes->GetNumberOfProxies(); ++i)
    if (vtkSMProxy* mesh = meshes->GetProxy(i))
    {
      this->Order.emplace_back(mesh);
      this->OrderModes.push_back(i < modes->GetNumberOfElements() ? modes->GetElement(i) : -1);
    }

  // The rows: the polygonal sources of this proxy's server, in the
  // pipeline's order, then any clip mesh that is not one of them.
  this->Sources.clear();
  std::vector<QString> labels;
  auto* model = pqApplicationCore::instance()->getServerManagerModel();
  auto* types = meshes->FindDomain<vtkSMDataTypeDomain>();
  for (pqPipelineSource* source : model->findItems<pqPipelineSource*>(model->findServer(proxy->GetSession())))
  {
    auto* sourceProxy = vtkSMSourceProxy::SafeDownCast(source->getProxy());
    const bool ticked = IndexOf(this->Order, sourceProxy) >= 0;
    if (!sourceProxy || (!ticked && (!types || !types->IsInDomain(sourceProxy, 0))))
      continue;
    this->Sources.emplace_back(sourceProxy);
    labels.push_back(source->getSMName());
    // (a filter's output type is known once it has run)
    QObject::connect(source, SIGNAL(dataUpdated(pqPipelineSource*)), this, SLOT(refresh()),
      static_cast<Qt::ConnectionType>(Qt::QueuedConnection | Qt::UniqueConnection));
  }
  for (const auto& mesh : this->Order)
    if (IndexOf(this->Sources, mesh.GetPointer()) < 0)
    {
      this->Sources.push_back(mesh);
      labels.push_back(QString("%1 (not in the pipeline)").arg(mesh->GetXMLLabel()));
    }

  this->Table->setRowCount(static_cast<int>(this->Sources.size()));
  for (int row = 0; row < static_cast<int>(this->Sources.size()); ++row)
  {
    const std::ptrdiff_t at = IndexOf(this->Order, this->Sources[row].GetPointer());
    auto* item = new QTableWidgetItem(labels[row]);
    item->setFlags(Qt::ItemIsEnabled | Qt::ItemIsUserCheckable);
    item->setCheckState(at >= 0 ? Qt::Checked : Qt::Unchecked);
    this->Table->setItem(row, 0, item);
    auto* combo = new QComboBox(this->Table);
    combo->setObjectName(QString("ClipMeshMode%1").arg(row));
    combo->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
    combo->setMinimumContentsLength(9);
    for (const char* name : ModeNames)
      combo->addItem(name);
    const int mode = at >= 0 ? this->OrderModes[at] : -1;
    combo->setCurrentIndex(mode >= -1 && mode <= 1 ? mode + 1 : 0);
    combo->setEnabled(at >= 0);
    QObject::connect(combo, QOverload<int>::of(&QComboBox::currentIndexChanged), this, &pqCAOClipMeshesWidget::edited);
    this->Table->setCellWidget(row, 1, combo);
  }
  int height = this->Table->horizontalHeader()->sizeHint().height() + 2 * this->Table->frameWidth();
  for (int row = 0; row < this->Table->rowCount(); ++row)
    height += this->Table->rowHeight(row);
  this->Table->setFixedHeight(height);
  this->Table->setVisible(!this->Sources.empty());
  this->Note->setText(this->Sources.empty()
      ? "No polygonal source in the pipeline yet: add one (a Sphere, an STL reader, a Contour), "
        "apply it, and tick it here to clip the volume with it."
      : "Ticked meshes clip too, beside Clip Shape; each must be closed.");
  this->Refreshing = false;
}

void pqCAOClipMeshesWidget::edited()
{
  if (this->Refreshing)
    return;
  // Meshes keep the order they were ticked in; a mode only with a tick.
  for (int row = 0; row < this->Table->rowCount(); ++row)
  {
    vtkSMProxy* source = this->Sources[row];
    const bool ticked = this->Table->item(row, 0)->checkState() == Qt::Checked;
    const std::ptrdiff_t at = IndexOf(this->Order, source);
    if (ticked && at < 0)
    {
      this->Order.emplace_back(source);
      this->OrderModes.push_back(-1);
    }
    else if (!ticked && at >= 0)
    {
      this->Order.erase(this->Order.begin() + at);
      this->OrderModes.erase(this->OrderModes.begin() + at);
    }
    if (QWidget* combo = this->Table->cellWidget(row, 1))
      combo->setEnabled(ticked);
  }
  Q_EMIT this->changeAvailable();
  Q_EMIT this->changeFinished();
}

void pqCAOClipMeshesWidget::rowsToLists(std::vector<vtkSMProxy*>& meshes, std::vector<int>& modes) const
{
  meshes.clear();
  modes.clear();
  for (std::size_t i = 0; i < this->Order.size(); ++i)
  {
    vtkSMProxy* mesh = this->Order[i];
    if (!mesh)
      continue; // (deleted since)
    const std::ptrdiff_t row = IndexOf(this->Sources, mesh);
    auto* combo = row >= 0 ? qobject_cast<QComboBox*>(this->Table->cellWidget(static_cast<int>(row), 1)) : nullptr;
    meshes.push_back(mesh);
    modes.push_back(combo ? combo->currentIndex() - 1 : this->OrderModes[i]);
  }
}

void pqCAOClipMeshesWidget::apply()
{
  vtkSMProxy* proxy = this->proxy();
  auto* meshes = proxy ? vtkSMProxyProperty::SafeDownCast(proxy->GetProperty(MeshesName)) : nullptr;
  auto* modes = proxy ? vtkSMIntVectorProperty::SafeDownCast(proxy->GetProperty(ModesName)) : nullptr;
  if (meshes && modes)
  {
    std::vector<vtkSMProxy*> meshList;
    std::vector<int> modeList;
    this->rowsToLists(meshList, modeList);
    // One undo step named for what changed (Edit > Undo Change Clip
    // Meshes), not for the proxy's class.
    SCOPED_UNDO_SET(tr("Change Clip Meshes"));
    this->Applying = true;
    meshes->SetProxies(static_cast<unsigned int>(meshList.size()), meshList.data());
    modes->SetNumberOfElements(static_cast<unsigned int>(modeList.size()));
    if (!modeList.empty())
      modes->SetElements(modeList.data());
    proxy->UpdateVTKObjects();
    this->Applying = false;
  }
  this->Superclass::apply();
}

void pqCAOClipMeshesWidget::showEvent(QShowEvent* event)
{
  this->Superclass::showEvent(event);
  if (!this->Panel)
  {
    for (QWidget* w = this->parentWidget(); w && !this->Panel; w = w->parentWidget())
      this->Panel = qobject_cast<QScrollArea*>(w);
    if (this->Panel)
      this->Panel->viewport()->installEventFilter(this);
  }
  this->fitToPanel();
}

bool pqCAOClipMeshesWidget::eventFilter(QObject* watched, QEvent* event)
{
  if (this->Panel && watched == this->Panel->viewport() && event->type() == QEvent::Resize)
    this->fitToPanel();
  return this->Superclass::eventFilter(watched, event);
}

void pqCAOClipMeshesWidget::fitToPanel()
{
  if (!this->Panel || !this->Panel->widget())
    return;
  const int left = this->mapTo(this->Panel->widget(), QPoint(0, 0)).x();
  this->setMaximumWidth(std::max(160, this->Panel->viewport()->width() - left - 4));
}

void pqCAOClipMeshesWidget::reset()
{
  this->refresh();
  this->Superclass::reset();
}
