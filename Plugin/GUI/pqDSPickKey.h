// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   pqDSPickKey
 * @brief   The P key over a render view, for a property widget: "pick what is under the cursor".
 *
 * ParaView's point-picking key is P over the render view (Ctrl+P: snap to the nearest mesh
 * point), as pqPointPickingHelper offers it to its interactive widgets. This helper gives the
 * same key to the plugin's panels, which pick more than a point (a seed point, a tetrahedron):
 * it emits pressed() with the view's interactor position of the cursor, only while its property
 * widget is on screen (the panel of the active source), so panels of other sources stay quiet.
 *
 * The key arrives by one of two ways: through the view's VTK interactor (on Linux ParaView's view
 * is a container around an OpenGL window, which hands the keys it gets to the interactor) or at
 * the view's Qt widget itself (keys sent to it, e.g. by ParaView's test player). Both are watched;
 * a key taken at the widget is consumed there, so it is never handled twice.
 */
#ifndef pqDSPickKey_h
#define pqDSPickKey_h

#include "vtkWeakPointer.h"

#include <QObject>
#include <QPointer>

class pqPropertyWidget;
class pqRenderView;
class pqView;
class vtkObject;
class vtkRenderWindowInteractor;

class pqDSPickKey : public QObject
{
  Q_OBJECT

public:
  explicit pqDSPickKey(pqPropertyWidget* owner);
  ~pqDSPickKey() override;

  /// Watches this view (a render view; any other view: none).
  void setView(pqView* view);
  pqRenderView* view() const;

Q_SIGNALS:
  /// P was pressed over the view at display position (x, y) (VTK pixels, origin bottom left).
  void pressed(int x, int y, bool control);

protected:
  bool eventFilter(QObject* watched, QEvent* event) override;

private:
  void onInteractorKey(vtkObject*, unsigned long, void*);
  void emitAtCursor(bool control);

  pqPropertyWidget* Owner;
  QPointer<pqRenderView> View;
  vtkWeakPointer<vtkRenderWindowInteractor> Interactor;
  unsigned long Observer = 0;
};

#endif
