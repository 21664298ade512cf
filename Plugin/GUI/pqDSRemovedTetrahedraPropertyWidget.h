// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   pqDSRemovedTetrahedraPropertyWidget
 * @brief   Delaunay Seed Surface's Removed Tetrahedra: P over a tetrahedron toggles it.
 *
 * The paper's slicing tool shows the Delaunay tetrahedra of the picked points and lets the user
 * click the ones to delete (Lürig, Kobbelt & Ertl 2000, section 7, Fig. 10). With this panel the
 * user shows the filter's Tetrahedra output (or a Slice or Clip of it, to reach inner
 * tetrahedra), puts the cursor on a tetrahedron and presses P (pqDSPickKey): its TetraId, read
 * from the picked cell, is added to the list, or taken out if it was in it. The list is the
 * `RemovedTetrahedra` property (applied with Apply, kept in state files); ids can still be typed.
 *
 * TetraIds number the tetrahedra of one tetrahedrisation: when the seed points change, the same
 * id names another tetrahedron. The panel notices it (the Tetrahedra output's counts, bounds and
 * circumradius range change, which removals and Alpha never change) and clears the list with a
 * warning, committed at once (the filter runs again without removals; it has run once with the
 * old ids by then). Keeping a removal by its corner points is left out: a changed point set
 * usually has none of the old tetrahedra near the change.
 *
 * It is the panel_widget "ds_removed_tetrahedra" of the IdTypeVectorProperty RemovedTetrahedra
 * (xml/DelaunaySeedSurface.xml).
 */
#ifndef pqDSRemovedTetrahedraPropertyWidget_h
#define pqDSRemovedTetrahedraPropertyWidget_h

#include "pqPropertyWidget.h"

#include <QList>
#include <QVariant>

#include <vector>

class QLabel;
class QLineEdit;
class pqDSPickKey;
class pqPipelineSource;
class vtkSMProperty;

class pqDSRemovedTetrahedraPropertyWidget : public pqPropertyWidget
{
  Q_OBJECT
  Q_PROPERTY(QList<QVariant> ids READ ids WRITE setIds NOTIFY idsChanged)
  typedef pqPropertyWidget Superclass;

public:
  pqDSRemovedTetrahedraPropertyWidget(
    vtkSMProxy* proxy, vtkSMProperty* smproperty, QWidget* parent = nullptr);
  ~pqDSRemovedTetrahedraPropertyWidget() override;

  ///@{
  /// The TetraIds, as the `RemovedTetrahedra` property holds them.
  QList<QVariant> ids() const;
  void setIds(const QList<QVariant>& values);
  ///@}

  void setView(pqView* view) override;

public Q_SLOTS:
  /// Adds `tetraId` to the list, or removes it if it is there.
  void toggle(vtkIdType tetraId);

Q_SIGNALS:
  void idsChanged();

private Q_SLOTS:
  void onTextEdited();
  void onDataUpdated();

private:
  Q_DISABLE_COPY(pqDSRemovedTetrahedraPropertyWidget)

  void pickAt(int x, int y);
  bool descendsFromTetrahedra(vtkSMProxy* source, unsigned int port, int depth) const;
  bool tetraIdAt(vtkSMProxy* source, unsigned int port, vtkSMProxy* selection, vtkIdType& id);
  std::vector<double> tetrahedrisation() const;
  void showIds();

  std::vector<vtkIdType> Ids;
  // The Tetrahedra output's counts, bounds and circumradius range when the ids were picked.
  std::vector<double> PickedOn;
  vtkSMProperty* RemovedTetrahedra = nullptr;
  QLineEdit* Text = nullptr;
  QLabel* Status = nullptr;
  pqDSPickKey* PickKey = nullptr;
};

#endif
