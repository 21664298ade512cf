// SPDX-License-Identifier: BSD-3-Clause
#include "pqDSClickToolBar.h"

#include "pqActiveObjects.h"
#include "pqApplicationCore.h"
#include "pqDataRepresentation.h"
#include "pqObjectBuilder.h"
#include "pqOutputPort.h"
#include "pqPipelineSource.h"
#include "pqServer.h"
#include "pqServerManagerModel.h"
#include "pqUndoStack.h"
#include "pqView.h"
#include "vtkNew.h"
#include "vtkPVDataInformation.h"
#include "vtkSMParaViewPipelineControllerWithRendering.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxy.h"
#include "vtkSMRepresentationProxy.h"
#include "vtkSMSessionProxyManager.h"
#include "vtkSMSourceProxy.h"
#include "vtkSMViewProxy.h"

#include <QAction>
#include <QDebug>
#include <QPointer>
#include <QTimer>

#include <cstring>

namespace
{
/// The representation of `port` in `view`, when it is shown there as an outline.
vtkSMProxy* OutlineShown(pqOutputPort* port, pqView* view)
{
  pqDataRepresentation* shown = view ? port->getRepresentation(view) : nullptr;
  if (!shown || !shown->isVisible())
  {
    return nullptr;
  }
  vtkSMProxy* proxy = shown->getProxy();
  const char* type = vtkSMPropertyHelper(proxy, "Representation", true).GetAsString();
  return type && std::strcmp(type, "Outline") == 0 ? proxy : nullptr;
}

/// Whether the server knows the DeformableSurface plugin's proxies (the base plugin is loaded).
bool FiltersLoaded(pqServer* server)
{
  vtkSMSessionProxyManager* proxies = server->proxyManager();
  return proxies->GetPrototypeProxy("sources", "SeedPoints") &&
    proxies->GetPrototypeProxy("filters", "DelaunaySeedSurface") &&
    proxies->GetPrototypeProxy("filters", "DeformableSurface");
}

/// Delaunay Seed Surface on `points` and Deformable Surface on it and `image`, the surface shown
/// in the active render view (the image's slice left shown, for more points), whenever `points`
/// has been applied with a point and feeds no filter: after the first such Apply, and again after
/// those filters were undone or deleted. It lives as long as `points`.
class ChainOnPoints : public QObject
{
public:
  ChainOnPoints(pqPipelineSource* points, pqOutputPort* image)
    : QObject(points)
    , Points(points)
    , Image(image)
  {
    // An Apply marks the points unmodified, also where it updates no data (a Seed Points hidden,
    // or brought back by Redo, which the Apply does not show).
    QObject::connect(points, &pqProxy::modifiedStateChanged, this, &ChainOnPoints::onApplied);
  }

private:
  void onApplied()
  {
    pqUndoStack* undo = pqApplicationCore::instance()->getUndoStack();
    if (this->Pending || this->Points->modifiedState() != pqProxy::UNMODIFIED ||
      (undo && (undo->getInUndo() || undo->getInRedo())))
    {
      return; // not an Apply: Undo or Redo bring back what they bring back
    }
    // After the Apply has finished (its properties pushed, its proxies shown): an undo step of
    // its own, and no proxy added while ParaView still shows the ones it applied.
    this->Pending = true;
    QTimer::singleShot(0, this, &ChainOnPoints::build);
  }

  void build()
  {
    this->Pending = false;
    if (!this->Image || this->Points->getNumberOfConsumers() > 0 ||
      vtkSMPropertyHelper(this->Points->getProxy(), "Points").GetNumberOfElements() < 3)
    {
      return; // the chain is there, or applied without a point
    }
    pqView* view = pqActiveObjects::instance().activeView(); // where P was pressed
    BEGIN_UNDO_SET(tr("Deformable Surface on the seed points"));
    pqObjectBuilder* builder = pqApplicationCore::instance()->getObjectBuilder();
    pqPipelineSource* seed = builder->createFilter("filters", "DelaunaySeedSurface", this->Points);
    pqPipelineSource* surface = nullptr;
    if (seed)
    {
      QMap<QString, QList<pqOutputPort*>> inputs;
      inputs["Input"].push_back(this->Image);
      inputs["InitialSurface"].push_back(seed->getOutputPort(0));
      surface =
        builder->createFilter("filters", "DeformableSurface", inputs, this->Image->getServer());
    }
    if (!surface)
    {
      if (seed)
      {
        builder->destroy(seed);
      }
      END_UNDO_SET();
      qWarning() << "Segment from points: Delaunay Seed Surface or Deformable Surface could not be "
                    "made (is the DeformableSurface plugin still loaded?)";
      return;
    }
    if (view)
    {
      vtkNew<vtkSMParaViewPipelineControllerWithRendering> controller;
      controller->Show(surface->getSourceProxy(), 0, view->getViewProxy());
    }
    // Shown, so applied: the Properties panel does not offer them to Apply again.
    seed->setModifiedState(pqProxy::UNMODIFIED);
    surface->setModifiedState(pqProxy::UNMODIFIED);
    END_UNDO_SET();
    if (view)
    {
      view->render();
    }
    pqActiveObjects::instance().setActiveSource(surface);
  }

  pqPipelineSource* Points;
  QPointer<pqOutputPort> Image;
  bool Pending = false;
};
}

pqDSClickToolBar::pqDSClickToolBar(QWidget* parent)
  : QToolBar(tr("Deformable Surface"), parent)
{
  this->setObjectName("DeformableSurfaceToolBar");
  QAction* segment = this->addAction(tr("Segment from points"));
  segment->setObjectName("actionDSSegmentFromPoints");
  segment->setToolTip(tr("Seed Points on the active image: press P over the object (one click) "
                         "or around it (picks), then Apply: Delaunay Seed Surface and Deformable "
                         "Surface follow."));
  // The test player finds a toolbar button by its object name (pqEventPlayer).
  if (QWidget* button = this->widgetForAction(segment))
  {
    button->setObjectName("actionDSSegmentFromPoints");
  }
  QObject::connect(segment, &QAction::triggered, this, &pqDSClickToolBar::segmentActiveImage);
  // Redo of the button's step makes its Seed Points again, with the same global id.
  QObject::connect(pqApplicationCore::instance()->getServerManagerModel(),
    &pqServerManagerModel::sourceAdded, this, &pqDSClickToolBar::watchAgain);
}

void pqDSClickToolBar::watchAgain(pqPipelineSource* source)
{
  auto image = this->ImageOfPoints.find(source->getProxy()->GetGlobalID());
  if (image != this->ImageOfPoints.end() && image.value())
  {
    new ChainOnPoints(source, image.value());
  }
}

void pqDSClickToolBar::segmentActiveImage()
{
  pqActiveObjects& active = pqActiveObjects::instance();
  pqOutputPort* image = active.activePort();
  vtkPVDataInformation* info = image ? image->getDataInformation() : nullptr;
  if (!info || !info->DataSetTypeIsA("vtkImageData"))
  {
    qWarning() << "Segment from points: the active source gives no image (apply a volume's "
                  "reader first and select it)";
    return;
  }
  if (!FiltersLoaded(image->getServer()))
  {
    qWarning() << "Segment from points: the DeformableSurface plugin's filters are not loaded "
                  "(Tools > Manage Plugins)";
    return;
  }
  // One step of Edit > Undo takes the points (and the representation's change) back.
  BEGIN_UNDO_SET(tr("Segment from points"));
  pqObjectBuilder* builder = pqApplicationCore::instance()->getObjectBuilder();
  pqPipelineSource* points = builder->createSource("sources", "SeedPoints", image->getServer());
  if (!points)
  {
    END_UNDO_SET();
    qWarning() << "Segment from points: Seed Points could not be made";
    return;
  }
  pqView* view = active.activeView();
  if (vtkSMProxy* outline = OutlineShown(image, view))
  {
    vtkSMRepresentationProxy::SetRepresentationType(outline, "Slice");
    view->render();
  }
  END_UNDO_SET();
  this->ImageOfPoints[points->getProxy()->GetGlobalID()] = image;
  new ChainOnPoints(points, image);
  active.setActiveSource(points);
}
