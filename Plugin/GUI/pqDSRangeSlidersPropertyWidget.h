// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   pqDSRangeSlidersPropertyWidget
 * @brief   Deformable Surface's Intensity Range as two sliders over the image's values.
 *
 * The region force grows the surface through the voxels whose value lies in the object's range
 * (docs/METHOD.md section 9.3); Preview Region shows what that range reaches before a solve.
 * ITK-SNAP and 3D Slicer set such a threshold with sliders over the image's values; this panel
 * does the same for the 2-element property `IntensityRange`: a low and a high slider
 * (pqDoubleRangeWidget, each with a text field that also takes values beyond the sliders), bounded
 * by the range of the image array the filter uses (its `Scalars` on its `Input`), read from the
 * input's data information. Moving one past the other moves the other along.
 *
 * The bounds are not a domain in the XML on purpose: a range domain would reset the property to
 * the array's range when a proxy is created (vtkSMRangeDomainTemplate::SetDefaultValues), so
 * pvpython would lose the default 0 0 (estimate the range from the start surface). Without this
 * plugin the client shows the default two number fields.
 *
 * Below the sliders the panel shows the range the last run used (the output's field data
 * IntensityRange: the estimate when the property is 0 0) and a button that takes it into the
 * sliders, so a user previews the estimate, then adjusts it.
 *
 * It is the panel_widget "ds_intensity_range" of the DoubleVectorProperty IntensityRange
 * (xml/DeformableSurface.xml).
 */
#ifndef pqDSRangeSlidersPropertyWidget_h
#define pqDSRangeSlidersPropertyWidget_h

#include "pqPropertyWidget.h"

#include <QPointer>

#include <array>

class QLabel;
class QPushButton;
class pqDoubleRangeWidget;
class pqPipelineSource;

class pqDSRangeSlidersPropertyWidget : public pqPropertyWidget
{
  Q_OBJECT
  typedef pqPropertyWidget Superclass;

public:
  pqDSRangeSlidersPropertyWidget(
    vtkSMProxy* proxy, vtkSMProperty* smproperty, QWidget* parent = nullptr);
  ~pqDSRangeSlidersPropertyWidget() override;

private Q_SLOTS:
  void onLowEdited(double value);
  void onHighEdited(double value);
  /// Bounds the sliders by the range of the image array the filter uses.
  void updateBounds();
  /// Shows the range the last run used.
  void updateUsed();
  void takeUsed();
  /// Follows the source connected to Input (it may be changed in the pipeline).
  void followInput();

private:
  Q_DISABLE_COPY(pqDSRangeSlidersPropertyWidget)

  bool scalarsRange(double range[2]) const;
  bool usedRange(double range[2]) const;

  pqDoubleRangeWidget* Low = nullptr;
  pqDoubleRangeWidget* High = nullptr;
  QLabel* Used = nullptr;
  QPushButton* TakeUsed = nullptr;
  QPointer<pqPipelineSource> Input;
  // The bounds the sliders have (each change of them makes new validators: only on a change).
  std::array<double, 2> Bounds = { { 1.0, 0.0 } };
};

#endif
