// SPDX-License-Identifier: BSD-3-Clause
#include "pqDSClickToolBar.h"

#include "pqActiveObjects.h"
#include "pqApplicationCore.h"
#include "pqDataRepresentation.h"
#include "pqObjectBuilder.h"
#include "pqOutputPort.h"
#include "pqPipelineSource.h"
#include "pqProxyModifiedStateUndoElement.h"
#include "pqRenderView.h"
#include "pqServer.h"
#include "pqServerManagerModel.h"
#include "pqUndoStack.h"
#include "pqView.h"
#include "vtkCommand.h"
#include "vtkNew.h"
#include "vtkPVDataInformation.h"
#include "vtkSMParaViewPipelineControllerWithRendering.h"
#include "vtkSMProperty.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxy.h"
#include "vtkSMRepresentationProxy.h"
#include "vtkSMSessionProxyManager.h"
#include "vtkSMSourceProxy.h"
#include "vtkSMViewProxy.h"
#include "vtkWeakPointer.h"

#include <QAction>
#include <QDebug>
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

/// The image's output port `image` names, if it is still there.
pqOutputPort* PortOf(const pqDSClickToolBar::ImageRef& image)
{
  auto* source =
    pqApplicationCore::instance()->getServerManagerModel()->findItem<pqPipelineSource*>(
      image.Source);
  return source && source->getServer() == image.Server &&
      image.Port < source->getNumberOfOutputPorts()
    ? source->getOutputPort(image.Port)
    : nullptr;
}

/// The render view to show the surface in: the active one (where P was pressed), else one that
/// shows the image.
pqView* RenderViewFor(pqOutputPort* image)
{
  if (auto* active = qobject_cast<pqRenderView*>(pqActiveObjects::instance().activeView()))
  {
    return active;
  }
  for (pqView* view : image->getViews())
  {
    if (qobject_cast<pqRenderView*>(view))
    {
      return view;
    }
  }
  return nullptr;
}

/// Marks `proxy` applied (its Properties panel does not offer it to Apply again), as an Apply
/// does, undo and redo included (pqApplyBehavior).
void MarkApplied(pqProxy* proxy)
{
  proxy->setModifiedState(pqProxy::UNMODIFIED);
  vtkNew<pqProxyModifiedStateUndoElement> undo;
  undo->SetSession(proxy->getServer()->session());
  undo->MadeUnmodified(proxy);
  ADD_UNDO_ELEM(undo);
}

/// Delaunay Seed Surface on `points` and Deformable Surface on it and the image, the surface
/// shown (the image's slice left shown, for more points), whenever an Apply has changed the
/// points' `Points`, they hold a point and they feed no filter: after the first such Apply, and
/// again after those filters were undone or deleted. It watches the property, not the data or
/// the panel's state: an Apply of hidden points updates no data, and the panel's Reset marks the
/// points unmodified without applying anything. It lives as long as `points`.
class ChainOnPoints : public QObject
{
public:
  ChainOnPoints(pqPipelineSource* points, const pqDSClickToolBar::ImageRef& image)
    : QObject(points)
    , Points(points)
    , Image(image)
  {
    this->Watched = points->getProxy()->GetProperty("Points");
    if (this->Watched)
    {
      this->Tag =
        this->Watched->AddObserver(vtkCommand::ModifiedEvent, this, &ChainOnPoints::onChanged);
    }
  }
  ~ChainOnPoints() override
  {
    if (this->Watched)
    {
      this->Watched->RemoveObserver(this->Tag);
    }
  }

private:
  void onChanged()
  {
    pqUndoStack* undo = pqApplicationCore::instance()->getUndoStack();
    if (this->Pending || (undo && (undo->getInUndo() || undo->getInRedo())))
    {
      return; // Undo and Redo bring back what they bring back
    }
    // After the Apply has finished (every property pushed, its proxies shown): an undo step of
    // its own, and no proxy added while ParaView still shows the ones it applied.
    this->Pending = true;
    QTimer::singleShot(0, this, &ChainOnPoints::build);
  }

  void build()
  {
    this->Pending = false;
    pqOutputPort* image = PortOf(this->Image);
    if (!image || this->Points->getNumberOfConsumers() > 0 ||
      vtkSMPropertyHelper(this->Points->getProxy(), "Points", true).GetNumberOfElements() < 3)
    {
      return; // the image is gone, the chain is there, or the points hold none
    }
    pqView* view = RenderViewFor(image);
    BEGIN_UNDO_SET(tr("Deformable Surface on the seed points"));
    pqObjectBuilder* builder = pqApplicationCore::instance()->getObjectBuilder();
    pqPipelineSource* seed = builder->createFilter("filters", "DelaunaySeedSurface", this->Points);
    pqPipelineSource* surface = nullptr;
    if (seed)
    {
      QMap<QString, QList<pqOutputPort*>> inputs;
      inputs["Input"].push_back(image);
      inputs["InitialSurface"].push_back(seed->getOutputPort(0));
      surface = builder->createFilter("filters", "DeformableSurface", inputs, image->getServer());
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
    MarkApplied(seed); // shown, so applied
    MarkApplied(surface);
    END_UNDO_SET();
    if (view)
    {
      view->render();
    }
    pqActiveObjects::instance().setActiveSource(surface);
  }

  pqPipelineSource* Points;
  pqDSClickToolBar::ImageRef Image;
  vtkWeakPointer<vtkSMProperty> Watched;
  unsigned long Tag = 0;
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
  const auto image = this->ImageOfPoints.constFind(source->getProxy()->GetGlobalID());
  if (image != this->ImageOfPoints.constEnd() && image->Server == source->getServer() &&
    std::strcmp(source->getProxy()->GetXMLName(), "SeedPoints") == 0)
  {
    new ChainOnPoints(source, *image);
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
  const ImageRef ref{ image->getServer(), image->getSource()->getProxy()->GetGlobalID(),
    image->getPortNumber() };
  this->ImageOfPoints[points->getProxy()->GetGlobalID()] = ref;
  new ChainOnPoints(points, ref);
  active.setActiveSource(points);
}
