// SPDX-License-Identifier: BSD-3-Clause
#include "pqDSPickKey.h"

#include "pqPropertyWidget.h"
#include "pqRenderView.h"
#include "vtkCommand.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkSMRenderViewProxy.h"

#include <QEvent>
#include <QKeyEvent>
#include <QWidget>

#include <cstring>

pqDSPickKey::pqDSPickKey(pqPropertyWidget* owner)
  : QObject(owner)
  , Owner(owner)
{
}

pqDSPickKey::~pqDSPickKey()
{
  this->setView(nullptr);
}

void pqDSPickKey::setView(pqView* view)
{
  auto* renderView = qobject_cast<pqRenderView*>(view);
  if (renderView == this->View)
  {
    return;
  }
  if (this->View && this->View->widget())
  {
    this->View->widget()->removeEventFilter(this);
  }
  if (this->Interactor)
  {
    this->Interactor->RemoveObserver(this->Observer);
  }
  this->View = renderView;
  this->Interactor = renderView && renderView->getRenderViewProxy()
    ? renderView->getRenderViewProxy()->GetInteractor()
    : nullptr;
  this->Observer = this->Interactor
    ? this->Interactor->AddObserver(vtkCommand::KeyPressEvent, this, &pqDSPickKey::onInteractorKey)
    : 0;
  if (this->View && this->View->widget())
  {
    this->View->widget()->installEventFilter(this);
  }
}

bool pqDSPickKey::eventFilter(QObject* watched, QEvent* event)
{
  if (this->View && watched == this->View->widget() && event->type() == QEvent::KeyPress &&
    static_cast<QKeyEvent*>(event)->key() == Qt::Key_P && this->Owner->isVisible())
  {
    this->emitAtCursor((static_cast<QKeyEvent*>(event)->modifiers() & Qt::ControlModifier) != 0);
    return true;
  }
  return this->QObject::eventFilter(watched, event);
}

void pqDSPickKey::onInteractorKey(vtkObject*, unsigned long, void*)
{
  const char* key = this->Interactor ? this->Interactor->GetKeySym() : nullptr;
  if (key && this->Owner->isVisible() && (std::strcmp(key, "p") == 0 || std::strcmp(key, "P") == 0))
  {
    this->emitAtCursor(this->Interactor->GetControlKey() != 0);
  }
}

void pqDSPickKey::emitAtCursor(bool control)
{
  if (this->Interactor)
  {
    // The last mouse position the view saw: the cursor when the key was pressed over it.
    const int* position = this->Interactor->GetEventPosition();
    Q_EMIT this->pressed(position[0], position[1], control);
  }
}

pqRenderView* pqDSPickKey::view() const
{
  return this->View;
}
