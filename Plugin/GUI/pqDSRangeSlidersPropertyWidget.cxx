// SPDX-License-Identifier: BSD-3-Clause
#include "pqDSRangeSlidersPropertyWidget.h"

#include "pqApplicationCore.h"
#include "pqCoreUtilities.h"
#include "pqDoubleRangeWidget.h"
#include "pqPipelineSource.h"
#include "pqServerManagerModel.h"
#include "vtkCommand.h"
#include "vtkDataObject.h"
#include "vtkPVArrayInformation.h"
#include "vtkPVDataInformation.h"
#include "vtkSMProperty.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMSourceProxy.h"

#include <QGridLayout>
#include <QLabel>
#include <QPushButton>

namespace
{
// Slider steps across the image's range: 4 units of a CT's -1024..3071, a quarter of a unit of
// an 8-bit MRI's; the text fields take any value in between.
const int SliderResolution = 1000;

pqDoubleRangeWidget* NewSlider(const char* name, QWidget* parent)
{
  auto* slider = new pqDoubleRangeWidget(parent);
  slider->setObjectName(name);
  slider->setResolution(SliderResolution);
  slider->setStrictRange(false);
  return slider;
}
}

pqDSRangeSlidersPropertyWidget::pqDSRangeSlidersPropertyWidget(
  vtkSMProxy* smproxy, vtkSMProperty* smproperty, QWidget* parentObject)
  : Superclass(smproxy, parentObject)
{
  this->setChangeAvailableAsChangeFinished(true);
  auto* layout = new QGridLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  this->Low = NewSlider("IntensityRangeLow", this);
  this->High = NewSlider("IntensityRangeHigh", this);
  layout->addWidget(new QLabel(tr("low"), this), 0, 0);
  layout->addWidget(this->Low, 0, 1);
  layout->addWidget(new QLabel(tr("high"), this), 1, 0);
  layout->addWidget(this->High, 1, 1);
  this->Used = new QLabel(this);
  this->Used->setObjectName("IntensityRangeUsed");
  this->Used->setWordWrap(true);
  layout->addWidget(this->Used, 2, 0, 1, 2);
  this->TakeUsed = new QPushButton(tr("Use the range of the last run"), this);
  this->TakeUsed->setObjectName("IntensityRangeTakeUsed");
  this->TakeUsed->setToolTip(tr("Set the sliders to the range the last run used (the estimate "
                                "when low equals high), to adjust it from there."));
  layout->addWidget(this->TakeUsed, 3, 0, 1, 2);

  this->addPropertyLink(this->Low, "value", SIGNAL(valueChanged(double)), smproperty, 0);
  this->addPropertyLink(this->High, "value", SIGNAL(valueChanged(double)), smproperty, 1);
  QObject::connect(this->Low, &pqDoubleRangeWidget::valueEdited, this,
    &pqDSRangeSlidersPropertyWidget::onLowEdited);
  QObject::connect(this->High, &pqDoubleRangeWidget::valueEdited, this,
    &pqDSRangeSlidersPropertyWidget::onHighEdited);
  QObject::connect(
    this->TakeUsed, &QPushButton::clicked, this, &pqDSRangeSlidersPropertyWidget::takeUsed);

  if (vtkSMProperty* scalars = smproxy->GetProperty("Scalars"))
  {
    pqCoreUtilities::connect(
      scalars, vtkCommand::UncheckedPropertyModifiedEvent, this, SLOT(updateBounds()));
    pqCoreUtilities::connect(scalars, vtkCommand::ModifiedEvent, this, SLOT(updateBounds()));
  }
  if (vtkSMProperty* input = smproxy->GetProperty("Input"))
  {
    pqCoreUtilities::connect(input, vtkCommand::ModifiedEvent, this, SLOT(followInput()));
  }
  auto* model = pqApplicationCore::instance()->getServerManagerModel();
  if (auto* self = model->findItem<pqPipelineSource*>(smproxy))
  {
    QObject::connect(self, SIGNAL(dataUpdated(pqPipelineSource*)), this, SLOT(updateUsed()));
  }
  this->followInput();
  this->updateUsed();
}

pqDSRangeSlidersPropertyWidget::~pqDSRangeSlidersPropertyWidget() = default;

void pqDSRangeSlidersPropertyWidget::onLowEdited(double value)
{
  if (this->High->value() < value)
  {
    this->High->setValue(value);
  }
}

void pqDSRangeSlidersPropertyWidget::onHighEdited(double value)
{
  if (this->Low->value() > value)
  {
    this->Low->setValue(value);
  }
}

void pqDSRangeSlidersPropertyWidget::followInput()
{
  if (this->Input)
  {
    QObject::disconnect(this->Input, nullptr, this, nullptr);
  }
  vtkSMPropertyHelper input(this->proxy(), "Input", /*quiet=*/true);
  auto* model = pqApplicationCore::instance()->getServerManagerModel();
  this->Input =
    input.GetAsProxy() ? model->findItem<pqPipelineSource*>(input.GetAsProxy()) : nullptr;
  if (this->Input)
  {
    QObject::connect(
      this->Input, SIGNAL(dataUpdated(pqPipelineSource*)), this, SLOT(updateBounds()));
  }
  this->updateBounds();
}

bool pqDSRangeSlidersPropertyWidget::scalarsRange(double range[2]) const
{
  vtkSMPropertyHelper input(this->proxy(), "Input", /*quiet=*/true);
  auto* source = vtkSMSourceProxy::SafeDownCast(input.GetAsProxy());
  vtkSMProperty* scalars = this->proxy()->GetProperty("Scalars");
  if (!source || !scalars)
  {
    return false;
  }
  // The array chosen in the panel (unchecked: before Apply), element 4 of SetInputArrayToProcess.
  vtkSMPropertyHelper array(scalars);
  array.SetUseUnchecked(true);
  const char* name = array.GetAsString(4);
  vtkPVDataInformation* info = source->GetDataInformation(input.GetOutputPort());
  vtkPVArrayInformation* values = (info && name)
    ? info->GetArrayInformation(name, vtkDataObject::FIELD_ASSOCIATION_POINTS)
    : nullptr;
  if (!values || values->GetNumberOfComponents() < 1)
  {
    return false;
  }
  range[0] = values->GetComponentRange(0)[0];
  range[1] = values->GetComponentRange(0)[1];
  return range[0] <= range[1];
}

void pqDSRangeSlidersPropertyWidget::updateBounds()
{
  double range[2];
  if (!this->scalarsRange(range) || (range[0] == this->Bounds[0] && range[1] == this->Bounds[1]))
  {
    return; // no image information yet, or the same range: the sliders keep their bounds
  }
  this->Bounds = { range[0], range[1] };
  for (pqDoubleRangeWidget* slider : { this->Low, this->High })
  {
    slider->setMinimum(range[0]);
    slider->setMaximum(range[1]);
  }
  const QString tip = tr("The image's values run from %1 to %2.").arg(range[0]).arg(range[1]);
  this->Low->setToolTip(tip);
  this->High->setToolTip(tip);
}

bool pqDSRangeSlidersPropertyWidget::usedRange(double range[2]) const
{
  // The output's field data IntensityRange: one tuple of two components (low, high).
  auto* self = vtkSMSourceProxy::SafeDownCast(this->proxy());
  vtkPVDataInformation* info =
    (self && self->GetNumberOfOutputPorts() > 0) ? self->GetDataInformation(0) : nullptr;
  vtkPVArrayInformation* used = info
    ? info->GetArrayInformation("IntensityRange", vtkDataObject::FIELD_ASSOCIATION_NONE)
    : nullptr;
  if (!used || used->GetNumberOfComponents() != 2)
  {
    return false;
  }
  range[0] = used->GetComponentRange(0)[0];
  range[1] = used->GetComponentRange(1)[0];
  return true;
}

void pqDSRangeSlidersPropertyWidget::updateUsed()
{
  double range[2];
  const bool known = this->usedRange(range);
  this->TakeUsed->setEnabled(known);
  QString text = known ? tr("The last run used %1 to %2.").arg(range[0]).arg(range[1])
                       : tr("The last run used no region range.");
  if (this->Low->value() == this->High->value())
  {
    text += tr(" Low equal to high: estimated from the start surface.");
  }
  this->Used->setText(text);
}

void pqDSRangeSlidersPropertyWidget::takeUsed()
{
  double range[2];
  if (this->usedRange(range))
  {
    this->High->setValue(range[1]);
    this->Low->setValue(range[0]);
  }
}
