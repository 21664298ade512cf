// SPDX-License-Identifier: BSD-3-Clause
#include "pqDSRemovedTetrahedraPropertyWidget.h"

#include "pqApplicationCore.h"
#include "pqDSPickKey.h"
#include "pqPipelineSource.h"
#include "pqRenderView.h"
#include "pqServerManagerModel.h"
#include "vtkCollection.h"
#include "vtkDataObject.h"
#include "vtkNew.h"
#include "vtkPVArrayInformation.h"
#include "vtkPVDataInformation.h"
#include "vtkSMInputProperty.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMRenderViewProxy.h"
#include "vtkSMSessionProxyManager.h"
#include "vtkSMSourceProxy.h"
#include "vtkSmartPointer.h"

#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QVBoxLayout>

#include <algorithm>

pqDSRemovedTetrahedraPropertyWidget::pqDSRemovedTetrahedraPropertyWidget(
  vtkSMProxy* smproxy, vtkSMProperty* smproperty, QWidget* parentObject)
  : Superclass(smproxy, parentObject)
{
  this->setChangeAvailableAsChangeFinished(true);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  auto* help = new QLabel(tr("<b>P</b> over a tetrahedron of the Tetrahedra output (or of a "
                             "slice of it): remove it, or keep it again."),
    this);
  help->setWordWrap(true);
  layout->addWidget(help);
  this->Text = new QLineEdit(this);
  this->Text->setObjectName("RemovedTetrahedraIds");
  this->Text->setToolTip(tr("TetraIds, separated by spaces."));
  layout->addWidget(this->Text);
  QObject::connect(this->Text, &QLineEdit::editingFinished, this,
    &pqDSRemovedTetrahedraPropertyWidget::onTextEdited);
  auto* clear = new QPushButton(tr("Keep all"), this);
  clear->setObjectName("RemovedTetrahedraClear");
  QObject::connect(
    clear, &QPushButton::clicked, this, [this]() { this->setIds({}), Q_EMIT this->idsChanged(); });
  layout->addWidget(clear);
  this->Status = new QLabel(this);
  this->Status->setObjectName("RemovedTetrahedraStatus");
  this->Status->setWordWrap(true);
  layout->addWidget(this->Status);

  this->PickKey = new pqDSPickKey(this);
  QObject::connect(
    this->PickKey, &pqDSPickKey::pressed, this, [this](int x, int y, bool) { this->pickAt(x, y); });
  this->RemovedTetrahedra = smproperty;
  this->addPropertyLink(this, "ids", SIGNAL(idsChanged()), smproperty);

  auto* model = pqApplicationCore::instance()->getServerManagerModel();
  if (auto* source = model->findItem<pqPipelineSource*>(smproxy))
  {
    QObject::connect(source, SIGNAL(dataUpdated(pqPipelineSource*)), this, SLOT(onDataUpdated()));
  }
}

pqDSRemovedTetrahedraPropertyWidget::~pqDSRemovedTetrahedraPropertyWidget() = default;

QList<QVariant> pqDSRemovedTetrahedraPropertyWidget::ids() const
{
  QList<QVariant> values;
  for (vtkIdType id : this->Ids)
  {
    values << static_cast<qlonglong>(id);
  }
  return values;
}

void pqDSRemovedTetrahedraPropertyWidget::setIds(const QList<QVariant>& values)
{
  this->Ids.clear();
  for (const QVariant& v : values)
  {
    this->Ids.push_back(static_cast<vtkIdType>(v.toLongLong()));
  }
  this->showIds();
}

void pqDSRemovedTetrahedraPropertyWidget::showIds()
{
  QStringList words;
  for (vtkIdType id : this->Ids)
  {
    words << QString::number(id);
  }
  this->Text->setText(words.join(' '));
}

void pqDSRemovedTetrahedraPropertyWidget::onTextEdited()
{
  std::vector<vtkIdType> typed;
  for (const QString& word : this->Text->text().split(' ', Qt::SkipEmptyParts))
  {
    bool ok = false;
    const qlonglong id = word.toLongLong(&ok);
    if (!ok)
    {
      this->Status->setText(tr("'%1' is not a TetraId: the list is unchanged.").arg(word));
      this->showIds();
      return;
    }
    typed.push_back(static_cast<vtkIdType>(id));
  }
  if (typed != this->Ids)
  {
    this->Ids = typed;
    this->PickedOn = this->tetrahedrisation();
    Q_EMIT this->idsChanged();
  }
}

void pqDSRemovedTetrahedraPropertyWidget::toggle(vtkIdType tetraId)
{
  auto it = std::find(this->Ids.begin(), this->Ids.end(), tetraId);
  if (it == this->Ids.end())
  {
    this->Ids.push_back(tetraId);
    this->Status->setText(tr("Tetrahedron %1 removed (Apply).").arg(tetraId));
  }
  else
  {
    this->Ids.erase(it);
    this->Status->setText(tr("Tetrahedron %1 kept again (Apply).").arg(tetraId));
  }
  this->PickedOn = this->tetrahedrisation();
  this->showIds();
  Q_EMIT this->idsChanged();
}

void pqDSRemovedTetrahedraPropertyWidget::setView(pqView* view)
{
  this->Superclass::setView(view);
  this->PickKey->setView(view);
}

void pqDSRemovedTetrahedraPropertyWidget::pickAt(int x, int y)
{
  pqRenderView* view = this->PickKey->view();
  if (!view)
  {
    return;
  }
  int region[4] = { x, y, x, y };
  vtkNew<vtkCollection> representations;
  vtkNew<vtkCollection> selections;
  view->getRenderViewProxy()->SelectSurfaceCells(region, representations, selections, false);
  for (int i = 0; i < representations->GetNumberOfItems() && i < selections->GetNumberOfItems();
       ++i)
  {
    vtkSMPropertyHelper input(
      vtkSMProxy::SafeDownCast(representations->GetItemAsObject(i)), "Input");
    vtkIdType id = -1;
    if (this->descendsFromTetrahedra(input.GetAsProxy(), input.GetOutputPort(), 0) &&
      this->tetraIdAt(input.GetAsProxy(), input.GetOutputPort(),
        vtkSMProxy::SafeDownCast(selections->GetItemAsObject(i)), id))
    {
      this->toggle(id);
      return;
    }
  }
  this->Status->setText(tr("No tetrahedron of this filter under the cursor: show its "
                           "Tetrahedra output (or a slice of it) and point at a cell."));
}

bool pqDSRemovedTetrahedraPropertyWidget::descendsFromTetrahedra(
  vtkSMProxy* source, unsigned int port, int depth) const
{
  // The picked data is this filter's Tetrahedra output or is made from it (Slice, Clip,
  // Threshold...), so its TetraId names this filter's tetrahedra and not another seed's.
  if (!source || depth > 32)
  {
    return false;
  }
  if (source == this->proxy())
  {
    return port == 1;
  }
  auto* inputs = vtkSMInputProperty::SafeDownCast(source->GetProperty("Input"));
  for (unsigned int i = 0; inputs && i < inputs->GetNumberOfProxies(); ++i)
  {
    if (this->descendsFromTetrahedra(
          inputs->GetProxy(i), inputs->GetOutputPortForConnection(i), depth + 1))
    {
      return true;
    }
  }
  return false;
}

bool pqDSRemovedTetrahedraPropertyWidget::tetraIdAt(
  vtkSMProxy* source, unsigned int port, vtkSMProxy* selection, vtkIdType& id)
{
  // The picked cell's TetraId, read on the server through an extraction of the one cell: its
  // range is the id (the data information reaches the client in every ParaView setup).
  vtkSmartPointer<vtkSMSourceProxy> extract;
  extract.TakeReference(vtkSMSourceProxy::SafeDownCast(
    source->GetSessionProxyManager()->NewProxy("filters", "ExtractSelection")));
  if (!extract)
  {
    return false;
  }
  vtkSMPropertyHelper(extract, "Input").Set(source, port);
  vtkSMPropertyHelper(extract, "Selection").Set(selection);
  extract->UpdateVTKObjects();
  extract->UpdatePipeline();
  vtkPVDataInformation* info = extract->GetDataInformation(0);
  vtkPVArrayInformation* tetraIds =
    info ? info->GetArrayInformation("TetraId", vtkDataObject::FIELD_ASSOCIATION_CELLS) : nullptr;
  if (!tetraIds || info->GetNumberOfCells() < 1)
  {
    return false;
  }
  const double* range = tetraIds->GetComponentRange(0);
  if (range[0] != range[1])
  {
    this->Status->setText(tr("The cursor is on an edge between tetrahedra: point inside one."));
    return false;
  }
  id = static_cast<vtkIdType>(range[0]);
  return true;
}

std::vector<double> pqDSRemovedTetrahedraPropertyWidget::tetrahedrisation() const
{
  auto* source = vtkSMSourceProxy::SafeDownCast(this->proxy());
  vtkPVDataInformation* info = source ? source->GetDataInformation(1) : nullptr;
  if (!info)
  {
    return {};
  }
  std::vector<double> facts = { static_cast<double>(info->GetNumberOfCells()),
    static_cast<double>(info->GetNumberOfPoints()) };
  const double* bounds = info->GetBounds();
  facts.insert(facts.end(), bounds, bounds + 6);
  if (vtkPVArrayInformation* radius =
        info->GetArrayInformation("Circumradius", vtkDataObject::FIELD_ASSOCIATION_CELLS))
  {
    facts.insert(facts.end(), radius->GetComponentRange(0), radius->GetComponentRange(0) + 2);
  }
  return facts;
}

void pqDSRemovedTetrahedraPropertyWidget::onDataUpdated()
{
  const std::vector<double> now = this->tetrahedrisation();
  if (this->PickedOn.empty())
  {
    this->PickedOn = now; // ids from a state file or Python: taken as meant for this complex
    return;
  }
  if (now == this->PickedOn)
  {
    return;
  }
  this->PickedOn = now;
  if (this->Ids.empty())
  {
    return;
  }
  // Committed at once, not left for Apply: the panel would take the applied (stale) ids back
  // when the Apply that changed the points resets the panels.
  this->Status->setText(tr("The tetrahedrisation changed (its points did): the TetraIds now "
                           "name other tetrahedra, so the %1 removed were cleared.")
                          .arg(this->Ids.size()));
  this->setIds({});
  vtkSMPropertyHelper(this->RemovedTetrahedra).SetNumberOfElements(0);
  this->proxy()->UpdateVTKObjects();
  auto* model = pqApplicationCore::instance()->getServerManagerModel();
  if (auto* source = model->findItem<pqPipelineSource*>(this->proxy()))
  {
    source->renderAllViews();
  }
}
