// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   pqDSSeedPointsPropertyWidget
 * @brief   The Seed Points panel: the points in a table; P in the render view adds one.
 *
 * The paper's slicing tool (Lürig, Kobbelt & Ertl 2000, section 7, Fig. 10) lets the user click
 * boundary points on slices. This panel does that for the Seed Points source (vtkDSSeedPoints):
 * - P with the cursor over the render view adds the point of the surface under the cursor (a
 *   slice, a volume's outline, any surface shown), Ctrl+P the nearest mesh point of it: the keys
 *   and the pick of ParaView's own point picking (pqPointPickingHelper), active while this panel
 *   is shown (pqDSPickKey); where that selection finds nothing, the point drawn there, from the
 *   depth buffer, if it lies on a dataset shown (an image shown as a Slice representation, which
 *   the selection does not see; Ctrl+P does not snap there, and with remote rendering the
 *   client's depth buffer holds nothing to pick);
 * - the new point seeds the object set in the "object" spin box (the ObjectId column);
 * - the table shows x, y, z and object per point; cells can be edited; Delete (or the remove
 *   button) removes the selected rows.
 * - the selected row's point carries a point handle: drag it in the view to move that point. Its
 *   representation proxy, DSSeedPointHandleRepresentation, lives in the base plugin's XML
 *   (xml/SeedPoints.xml, loaded by every client and server, Qt-free), inheriting ParaView's
 *   HandleWidgetRepresentation (that of pqHandlePropertyWidget) rather than copying it.
 * Every change is a property change, applied with Apply, so undo/redo and state files hold it.
 *
 * It is the panel_widget "ds_seed_points" of a property group holding the DoubleVectorProperty
 * `Points` (x y z per point) and the IntVectorProperty `ObjectIds` (xml/SeedPoints.xml).
 */
#ifndef pqDSSeedPointsPropertyWidget_h
#define pqDSSeedPointsPropertyWidget_h

#include "pqInteractivePropertyWidget.h"

#include <QList>
#include <QVariant>

#include <array>
#include <vector>

class QLabel;
class QSpinBox;
class QTableWidget;
class pqDSPickKey;
class vtkSMPropertyGroup;

class pqDSSeedPointsPropertyWidget : public pqInteractivePropertyWidget
{
  Q_OBJECT
  Q_PROPERTY(QList<QVariant> points READ points WRITE setPoints NOTIFY pointsChanged)
  Q_PROPERTY(QList<QVariant> objectIds READ objectIds WRITE setObjectIds NOTIFY pointsChanged)
  typedef pqInteractivePropertyWidget Superclass;

public:
  pqDSSeedPointsPropertyWidget(
    vtkSMProxy* proxy, vtkSMPropertyGroup* smgroup, QWidget* parent = nullptr);
  ~pqDSSeedPointsPropertyWidget() override;

  ///@{
  /// x y z per point, as the `Points` property holds them.
  QList<QVariant> points() const;
  void setPoints(const QList<QVariant>& values);
  ///@}

  ///@{
  /// One object per point, as the `ObjectIds` property holds them.
  QList<QVariant> objectIds() const;
  void setObjectIds(const QList<QVariant>& values);
  ///@}

  /// Follows the active view: the pick keys work in the active render view.
  void setView(pqView* view) override;

public Q_SLOTS:
  /// Appends a point seeding the object of the spin box.
  void addPoint(double x, double y, double z);
  /// Removes the rows selected in the table.
  void removeSelectedPoints();
  void removeAllPoints();

Q_SIGNALS:
  void pointsChanged();

protected:
  bool eventFilter(QObject* watched, QEvent* event) override;

protected Q_SLOTS:
  /// The handle sits on the selected row's point (nothing to place from data bounds).
  void placeWidget() override;

private Q_SLOTS:
  void onCellChanged(int row, int column);
  void onHandleMoved();

private:
  Q_DISABLE_COPY(pqDSSeedPointsPropertyWidget)

  void pickAt(int x, int y, bool snapToMeshPoint);
  void fillTable();

  std::vector<std::array<double, 3>> Points;
  // Kept as given (it may arrive before the points it belongs to); a missing entry is object 0.
  std::vector<int> ObjectIds;
  QTableWidget* Table = nullptr;
  QSpinBox* Object = nullptr;
  QLabel* Status = nullptr;
  pqDSPickKey* PickKey = nullptr;
  bool Filling = false;
};

#endif
