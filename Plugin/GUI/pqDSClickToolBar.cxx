// SPDX-License-Identifier: BSD-3-Clause
#include "pqDSClickToolBar.h"

#include "pqActiveObjects.h"
#include "pqApplicationCore.h"
#include "pqDataRepresentation.h"
#include "pqObjectBuilder.h"
#include "pqOutputPort.h"
#include "pqPipelineSource.h"
#include "pqRenderView.h"
#include "pqServer.h"
#include "pqUndoStack.h"
#include "vtkPVDataInformation.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxy.h"
#include "vtkSMRepresentationProxy.h"

#include <QAction>
#include <QDebug>

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
}

pqDSClickToolBar::pqDSClickToolBar(QWidget* parent)
  : QToolBar(tr("Deformable Surface"), parent)
{
  this->setObjectName("DeformableSurfaceToolBar");
  QAction* segment = this->addAction(tr("Segment from points"));
  segment->setObjectName("actionDSSegmentFromPoints");
  segment->setToolTip(tr("Seed Points -> Delaunay Seed Surface -> Deformable Surface on the "
                         "active image: press P over the object (one click) or around it "
                         "(picks), then Apply."));
  // The test player finds a toolbar button by its object name (pqEventPlayer).
  if (QWidget* button = this->widgetForAction(segment))
  {
    button->setObjectName("actionDSSegmentFromPoints");
  }
  QObject::connect(segment, &QAction::triggered, this, &pqDSClickToolBar::segmentActiveImage);
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
  // One step of Edit > Undo takes the whole chain (and the representation's change) back.
  BEGIN_UNDO_SET(tr("Segment from points"));
  pqServer* server = image->getServer();
  pqObjectBuilder* builder = pqApplicationCore::instance()->getObjectBuilder();
  pqPipelineSource* points = builder->createSource("sources", "SeedPoints", server);
  pqPipelineSource* seed =
    points ? builder->createFilter("filters", "DelaunaySeedSurface", points) : nullptr;
  if (!seed)
  {
    if (points)
    {
      builder->destroy(points);
    }
    END_UNDO_SET();
    qWarning() << "Segment from points: the DeformableSurface plugin's filters are not loaded "
                  "(Tools > Manage Plugins)";
    return;
  }
  QMap<QString, QList<pqOutputPort*>> inputs;
  inputs["Input"].push_back(image);
  inputs["InitialSurface"].push_back(seed->getOutputPort(0));
  builder->createFilter("filters", "DeformableSurface", inputs, server);
  if (vtkSMProxy* outline = OutlineShown(image, active.activeView()))
  {
    vtkSMRepresentationProxy::SetRepresentationType(outline, "Slice");
    active.activeView()->render();
  }
  END_UNDO_SET();
  active.setActiveSource(points);
}
