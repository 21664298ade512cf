// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   pqDSClickToolBar
 * @brief   The Deformable Surface toolbar: one button sets up a segmentation of the active image.
 *
 * ITK-SNAP and 3D Slicer place a seed with one click and run their snake from it. Here the chain
 * is three proxies: Seed Points -> Delaunay Seed Surface -> Deformable Surface (the image as its
 * Input). The button "Segment from points" starts it on the active source, which must give an
 * image: it adds Seed Points, shows the image as a Slice in the active render view when it is
 * shown as an outline (a surface for the P key), and makes Seed Points active, so its panel
 * takes P over the view. The first Apply that gives Seed Points a point then adds Delaunay Seed
 * Surface and Deformable Surface, every property at their defaults, and shows the surface: one P
 * (a click: a sphere grown to the object) or several (picks around it). The two filters come
 * after the points because a Delaunay Seed Surface applied together with still empty Seed Points
 * ran on no points and logged an error. They come again at the next Apply that changes the points
 * when they were undone or deleted, also when the points are hidden or were brought back by Redo
 * of the button itself (the points' `Points` property is watched, not their data; an Undo, a Redo
 * or the panel's Reset makes none). A Seed Points from a state file is a plain source. On
 * a source that gives no image, or without the DeformableSurface plugin's filters, it does nothing
 * but say so in the Output Messages.
 *
 * From a fresh client with the plugins loaded, the one-click workflow is then five actions: open
 * the volume, Apply, the button, P over the object, Apply (docs/GUI.md).
 */
#ifndef pqDSClickToolBar_h
#define pqDSClickToolBar_h

#include <QMap>
#include <QPointer>
#include <QToolBar>

#include "vtkType.h"

class pqPipelineSource;
class pqServer;

class pqDSClickToolBar : public QToolBar
{
  Q_OBJECT

public:
  explicit pqDSClickToolBar(QWidget* parent = nullptr);

  /// An image by its source's global id and output port (the port object itself is made anew
  /// when Undo and Redo take the image away and bring it back).
  struct ImageRef
  {
    QPointer<pqServer> Server;
    vtkTypeUInt32 Source = 0;
    int Port = 0;
  };

private:
  void segmentActiveImage();
  /// Watches `source` again when it is a Seed Points the button made (brought back by Redo).
  void watchAgain(pqPipelineSource* source);

  /// The image each Seed Points the button made segments, by the points' global id.
  QMap<vtkTypeUInt32, ImageRef> ImageOfPoints;
};

#endif
