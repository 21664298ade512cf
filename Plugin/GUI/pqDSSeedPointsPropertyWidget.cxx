// SPDX-License-Identifier: BSD-3-Clause
#include "pqDSSeedPointsPropertyWidget.h"

#include "pqDSPickKey.h"
#include "pqDataRepresentation.h"
#include "pqRenderView.h"
#include "vtkPVDataInformation.h"
#include "vtkRenderer.h"
#include "vtkSMNewWidgetRepresentationProxy.h"
#include "vtkSMPropertyGroup.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxy.h"
#include "vtkSMRenderViewProxy.h"

#include <QEvent>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QKeyEvent>
#include <QLabel>
#include <QPushButton>
#include <QSpinBox>
#include <QTableWidget>
#include <QVBoxLayout>

#include <algorithm>
#include <cmath>
#include <set>

namespace
{
const int ObjectColumn = 3;

/// Whether `p` lies within the bounds of a dataset the view shows (not on the orientation axes,
/// a widget's handle or the background).
bool OnShownData(pqRenderView* view, const double p[3])
{
  for (pqRepresentation* r : view->getRepresentations())
  {
    auto* shown = qobject_cast<pqDataRepresentation*>(r);
    vtkPVDataInformation* info =
      shown && shown->isVisible() ? shown->getInputDataInformation() : nullptr;
    const double* b = info ? info->GetBounds() : nullptr;
    if (!b)
    {
      continue;
    }
    // The depth buffer's precision, not the bounds', limits the slack: a thousandth of the
    // bounds' diagonal (a flat image's slice lies within it).
    const double slack = 1e-3 *
      std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) +
        (b[5] - b[4]) * (b[5] - b[4]));
    bool inside = true;
    for (int a = 0; a < 3; ++a)
    {
      inside = inside && p[a] >= b[2 * a] - slack && p[a] <= b[2 * a + 1] + slack;
    }
    if (inside)
    {
      return true;
    }
  }
  return false;
}

/// The world point drawn at display position (x, y): the depth buffer there, back through the
/// camera, when it lies on a dataset the view shows. An image shown as a Slice representation is
/// drawn by a mapper that ParaView's surface selection (ConvertDisplayToPointOnSurface) does not
/// see. The depth buffer holds what the client rendered: with remote rendering (client and
/// server) it holds no geometry of the server's and nothing is picked this way.
bool DepthPick(pqRenderView* view, int x, int y, double world[3])
{
  vtkRenderer* renderer = view->getRenderViewProxy()->GetRenderer();
  if (!renderer)
  {
    return false;
  }
  const double z = renderer->GetZ(x, y);
  if (!(z < 1.0))
  {
    return false;
  }
  renderer->SetDisplayPoint(x, y, z);
  renderer->DisplayToWorld();
  double point[4];
  renderer->GetWorldPoint(point);
  if (point[3] == 0.0)
  {
    return false;
  }
  for (int a = 0; a < 3; ++a)
  {
    world[a] = point[a] / point[3];
  }
  return OnShownData(view, world);
}

QTableWidgetItem* NumberItem(double value)
{
  // 'g' with 10 digits shows sub-voxel picks in millimetres without noise; the model keeps
  // the full double, so an unedited row is never rounded.
  return new QTableWidgetItem(QString::number(value, 'g', 10));
}
}

pqDSSeedPointsPropertyWidget::pqDSSeedPointsPropertyWidget(
  vtkSMProxy* smproxy, vtkSMPropertyGroup* smgroup, QWidget* parentObject)
  : Superclass("representations", "DSSeedPointHandleRepresentation", smproxy, smgroup, parentObject)
{
  this->setShowLabel(false);
  this->setChangeAvailableAsChangeFinished(true);

  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  auto* help = new QLabel(
    tr("<b>P</b> over the render view: add the point under the cursor (<b>Ctrl+P</b>: the "
       "nearest mesh point). <b>Delete</b>: remove the selected rows."),
    this);
  help->setWordWrap(true);
  layout->addWidget(help);

  this->Table = new QTableWidget(0, 4, this);
  this->Table->setObjectName("SeedPointsTable");
  this->Table->setHorizontalHeaderLabels({ "x", "y", "z", tr("object") });
  this->Table->horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
  this->Table->setSelectionBehavior(QAbstractItemView::SelectRows);
  this->Table->installEventFilter(this);
  layout->addWidget(this->Table);
  QObject::connect(
    this->Table, &QTableWidget::cellChanged, this, &pqDSSeedPointsPropertyWidget::onCellChanged);
  QObject::connect(this->Table, &QTableWidget::currentCellChanged, this,
    &pqDSSeedPointsPropertyWidget::placeWidget);
  QObject::connect(this, &pqInteractivePropertyWidgetAbstract::endInteraction, this,
    &pqDSSeedPointsPropertyWidget::onHandleMoved);

  auto* row = new QHBoxLayout();
  row->addWidget(new QLabel(tr("object"), this));
  this->Object = new QSpinBox(this);
  this->Object->setObjectName("SeedPointsObject");
  this->Object->setRange(0, 1000000);
  this->Object->setToolTip(tr("The object the next picked point seeds (its ObjectId)."));
  row->addWidget(this->Object);
  row->addStretch();
  auto* remove = new QPushButton(tr("Remove"), this);
  remove->setObjectName("SeedPointsRemove");
  QObject::connect(
    remove, &QPushButton::clicked, this, &pqDSSeedPointsPropertyWidget::removeSelectedPoints);
  row->addWidget(remove);
  auto* clear = new QPushButton(tr("Remove all"), this);
  clear->setObjectName("SeedPointsRemoveAll");
  QObject::connect(
    clear, &QPushButton::clicked, this, &pqDSSeedPointsPropertyWidget::removeAllPoints);
  row->addWidget(clear);
  layout->addLayout(row);

  this->PickKey = new pqDSPickKey(this);
  QObject::connect(
    this->PickKey, &pqDSPickKey::pressed, this, &pqDSSeedPointsPropertyWidget::pickAt);

  this->Status = new QLabel(this);
  this->Status->setObjectName("SeedPointsStatus");
  layout->addWidget(this->Status);

  this->addPropertyLink(this, "points", SIGNAL(pointsChanged()),
    smgroup->GetProperty("Points") ? smgroup->GetProperty("Points")
                                   : smproxy->GetProperty("Points"));
  this->addPropertyLink(this, "objectIds", SIGNAL(pointsChanged()),
    smgroup->GetProperty("ObjectIds") ? smgroup->GetProperty("ObjectIds")
                                      : smproxy->GetProperty("ObjectIds"));
}

pqDSSeedPointsPropertyWidget::~pqDSSeedPointsPropertyWidget() = default;

QList<QVariant> pqDSSeedPointsPropertyWidget::points() const
{
  QList<QVariant> values;
  for (const auto& p : this->Points)
  {
    values << p[0] << p[1] << p[2];
  }
  return values;
}

void pqDSSeedPointsPropertyWidget::setPoints(const QList<QVariant>& values)
{
  // A count that is not a multiple of 3 (typed in Python) cannot be shown as rows: the rows
  // show the complete triplets, the source reports the count.
  this->Points.clear();
  for (int i = 0; i + 2 < values.size(); i += 3)
  {
    this->Points.push_back(
      { values[i].toDouble(), values[i + 1].toDouble(), values[i + 2].toDouble() });
  }
  this->fillTable();
}

QList<QVariant> pqDSSeedPointsPropertyWidget::objectIds() const
{
  QList<QVariant> values;
  for (std::size_t i = 0; i < this->Points.size(); ++i)
  {
    values << (i < this->ObjectIds.size() ? this->ObjectIds[i] : 0);
  }
  return values;
}

void pqDSSeedPointsPropertyWidget::setObjectIds(const QList<QVariant>& values)
{
  this->ObjectIds.clear();
  for (const QVariant& v : values)
  {
    this->ObjectIds.push_back(v.toInt());
  }
  this->fillTable();
}

void pqDSSeedPointsPropertyWidget::fillTable()
{
  this->Filling = true;
  this->Table->setRowCount(static_cast<int>(this->Points.size()));
  for (int r = 0; r < this->Table->rowCount(); ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      this->Table->setItem(r, c, NumberItem(this->Points[r][c]));
    }
    const int object = r < static_cast<int>(this->ObjectIds.size()) ? this->ObjectIds[r] : 0;
    this->Table->setItem(r, ObjectColumn, new QTableWidgetItem(QString::number(object)));
  }
  this->Filling = false;
  this->Status->setText(tr("%1 point(s)").arg(this->Points.size()));
}

void pqDSSeedPointsPropertyWidget::onCellChanged(int row, int column)
{
  if (this->Filling || row < 0 || row >= static_cast<int>(this->Points.size()))
  {
    return;
  }
  bool ok = false;
  const QString text = this->Table->item(row, column)->text();
  if (column == ObjectColumn)
  {
    const int object = text.toInt(&ok);
    if (ok)
    {
      this->ObjectIds.resize(std::max(this->ObjectIds.size(), this->Points.size()), 0);
      this->ObjectIds[row] = object;
    }
  }
  else
  {
    const double value = text.toDouble(&ok);
    if (ok)
    {
      this->Points[row][column] = value;
    }
  }
  if (!ok)
  {
    this->Status->setText(tr("'%1' is not a number: the cell is reset.").arg(text));
  }
  this->fillTable();
  if (ok)
  {
    Q_EMIT this->pointsChanged();
  }
}

void pqDSSeedPointsPropertyWidget::addPoint(double x, double y, double z)
{
  this->ObjectIds.resize(this->Points.size(), 0);
  this->Points.push_back({ x, y, z });
  this->ObjectIds.push_back(this->Object->value());
  this->fillTable();
  this->Table->selectRow(this->Table->rowCount() - 1);
  Q_EMIT this->pointsChanged();
}

void pqDSSeedPointsPropertyWidget::removeSelectedPoints()
{
  std::set<int> rows;
  for (const QModelIndex& index : this->Table->selectionModel()->selectedRows())
  {
    rows.insert(index.row());
  }
  if (rows.empty())
  {
    return;
  }
  this->ObjectIds.resize(this->Points.size(), 0);
  // From the last row down, so the indices of the rows still to remove stay valid.
  for (auto r = rows.rbegin(); r != rows.rend(); ++r)
  {
    this->Points.erase(this->Points.begin() + *r);
    this->ObjectIds.erase(this->ObjectIds.begin() + *r);
  }
  this->fillTable();
  Q_EMIT this->pointsChanged();
}

void pqDSSeedPointsPropertyWidget::removeAllPoints()
{
  if (this->Points.empty() && this->ObjectIds.empty())
  {
    return;
  }
  this->Points.clear();
  this->ObjectIds.clear();
  this->fillTable();
  Q_EMIT this->pointsChanged();
}

bool pqDSSeedPointsPropertyWidget::eventFilter(QObject* watched, QEvent* event)
{
  // While a cell is edited, the editor (not the table) receives the keys.
  if (watched == this->Table && event->type() == QEvent::KeyPress)
  {
    const int key = static_cast<QKeyEvent*>(event)->key();
    if (key == Qt::Key_Delete || key == Qt::Key_Backspace)
    {
      this->removeSelectedPoints();
      return true;
    }
  }
  return this->Superclass::eventFilter(watched, event);
}

void pqDSSeedPointsPropertyWidget::setView(pqView* view)
{
  this->Superclass::setView(view);
  this->PickKey->setView(view);
}

void pqDSSeedPointsPropertyWidget::pickAt(int x, int y, bool snapToMeshPoint)
{
  pqRenderView* view = this->PickKey->view();
  if (!view)
  {
    return;
  }
  // The depth first: the surface selection renders passes of its own into the same buffers, and
  // read after one that ran (a second P once Seed Points shows its points) it was the background.
  double drawn[3];
  const bool onDrawn = DepthPick(view, x, y, drawn);
  const int position[2] = { x, y };
  double world[3], normal[3];
  if (view->getRenderViewProxy()->ConvertDisplayToPointOnSurface(
        position, world, normal, snapToMeshPoint))
  {
    this->addPoint(world[0], world[1], world[2]);
  }
  else if (onDrawn)
  {
    this->addPoint(drawn[0], drawn[1], drawn[2]);
  }
  else
  {
    this->Status->setText(tr("Nothing under the cursor to pick."));
  }
}

void pqDSSeedPointsPropertyWidget::placeWidget()
{
  const int row = this->Table->currentRow();
  const bool onPoint = row >= 0 && row < static_cast<int>(this->Points.size());
  if (onPoint)
  {
    vtkSMNewWidgetRepresentationProxy* handle = this->widgetProxy();
    vtkSMPropertyHelper(handle, "WorldPosition").Set(this->Points[row].data(), 3);
    handle->UpdateVTKObjects();
  }
  this->setWidgetVisible(onPoint);
  this->render();
}

void pqDSSeedPointsPropertyWidget::onHandleMoved()
{
  const int row = this->Table->currentRow();
  if (row < 0 || row >= static_cast<int>(this->Points.size()))
  {
    return;
  }
  vtkSMNewWidgetRepresentationProxy* handle = this->widgetProxy();
  handle->UpdatePropertyInformation();
  vtkSMPropertyHelper(handle, "WorldPositionInfo").Get(this->Points[row].data(), 3);
  this->fillTable();
  this->Table->selectRow(row);
  Q_EMIT this->pointsChanged();
}
