// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   pqDSClickToolBar
 * @brief   The Deformable Surface toolbar: one button sets up a segmentation of the active image.
 *
 * ITK-SNAP and 3D Slicer place a seed with one click and run their snake from it. Here the chain
 * is three proxies: Seed Points -> Delaunay Seed Surface -> Deformable Surface (the image as its
 * Input). The button "Segment from points" builds that chain on the active source, which must
 * give an image, every property at its default, shows the image as a Slice in the active render
 * view when it is shown as an outline (a surface for the P key), and makes Seed Points active,
 * so its panel takes P over the view. One P (a click: a sphere grown to the object) or several
 * (picks around it), then Apply applies the three. On a source that gives no image it does
 * nothing but say so in the Output Messages.
 *
 * From a fresh client with the plugins loaded, the one-click workflow is then five actions: open
 * the volume, Apply, the button, P over the object, Apply (docs/GUI.md).
 */
#ifndef pqDSClickToolBar_h
#define pqDSClickToolBar_h

#include <QToolBar>

class pqDSClickToolBar : public QToolBar
{
  Q_OBJECT

public:
  explicit pqDSClickToolBar(QWidget* parent = nullptr);

private:
  void segmentActiveImage();
};

#endif
