#include "vtk_view.h"

#include <algorithm>
#include <cmath>

#include <QMouseEvent>
#include <QOpenGLContext>
#include <QOpenGLFunctions>
#include <QWheelEvent>

#include <vtkActor.h>
#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellPicker.h>
#include <vtkCubeSource.h>
#include <vtkFloatArray.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkGenericRenderWindowInteractor.h>
#include <vtkGeometryFilter.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkLookupTable.h>
#include <vtkOpenGLState.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkSphereSource.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkUnstructuredGrid.h>

namespace palpation::ui {

namespace {
// Fingertip colours (HandHIRO order: thumb, index, middle, ring, little).
const double kFingerColour[5][3] = {{0.95, 0.75, 0.2}, {0.2, 0.55, 0.95}, {0.3, 0.8, 0.4}, {0.75, 0.45, 0.9}, {0.9, 0.4, 0.5}};
}  // namespace

VtkView::VtkView(QWidget* parent) : QOpenGLWidget(parent) {
  setMouseTracking(true);
  setFocusPolicy(Qt::StrongFocus);
  setMinimumSize(320, 240);
  window_->SetReadyForRendering(false);
  window_->SetFrameBlitModeToNoBlit();
  window_->SetStereoCapableWindow(1);
  window_->SetMultiSamples(0);
  window_->AddRenderer(renderer_);
  interactor_->SetRenderWindow(window_);
  vtkNew<vtkInteractorStyleTrackballCamera> style;
  interactor_->SetInteractorStyle(style);
  interactor_->EnableRenderOff();

  // VTK asks for the context through these events (stack-notes.md).
  auto make_current = vtkSmartPointer<vtkCallbackCommand>::New();
  make_current->SetClientData(this);
  make_current->SetCallback([](vtkObject*, unsigned long, void* self, void*) {
    auto* w = static_cast<VtkView*>(self);
    if (w->context()) w->context()->makeCurrent(w->context()->surface());
  });
  window_->AddObserver(vtkCommand::WindowMakeCurrentEvent, make_current);
  auto is_current = vtkSmartPointer<vtkCallbackCommand>::New();
  is_current->SetClientData(this);
  is_current->SetCallback([](vtkObject*, unsigned long, void* self, void* call_data) {
    auto* w = static_cast<VtkView*>(self);
    *static_cast<bool*>(call_data) = w->context() && QOpenGLContext::currentContext() == w->context();
  });
  window_->AddObserver(vtkCommand::WindowIsCurrentEvent, is_current);
  auto frame = vtkSmartPointer<vtkCallbackCommand>::New();
  frame->SetClientData(this);
  frame->SetCallback([](vtkObject*, unsigned long, void* self, void*) { static_cast<VtkView*>(self)->update(); });
  window_->AddObserver(vtkCommand::WindowFrameEvent, frame);

  renderer_->SetBackground(0.13, 0.15, 0.19);
  renderer_->SetBackground2(0.32, 0.36, 0.44);
  renderer_->GradientBackgroundOn();

  // Breast surface: all nodes as points (the snapshot's layout), surface triangles as cells.
  surface_->SetPoints(points_);
  displacement_->SetName("displacement");
  normals_->SetInputData(surface_);
  normals_->SplittingOff();
  normals_->ConsistencyOff();
  vtkNew<vtkPolyDataMapper> sm;
  sm->SetInputConnection(normals_->GetOutputPort());
  sm->ScalarVisibilityOff();
  vtkNew<vtkLookupTable> lut;
  lut->SetHueRange(0.66, 0.0);
  lut->Build();
  sm->SetLookupTable(lut);
  sm->SetScalarRange(0.0, 0.015);
  surface_actor_->SetMapper(sm);
  surface_actor_->GetProperty()->SetColor(0.96, 0.80, 0.70);
  surface_actor_->GetProperty()->SetSpecular(0.2);
  surface_actor_->GetProperty()->SetSpecularPower(20);
  surface_actor_->GetProperty()->SetOpacity(0.6);
  renderer_->AddActor(surface_actor_);

  // Tumours: the stiff elements, sharing the deformed points.
  tumour_grid_->SetPoints(points_);
  vtkNew<vtkGeometryFilter> tf;
  tf->SetInputData(tumour_grid_);
  vtkNew<vtkPolyDataMapper> tm;
  tm->SetInputConnection(tf->GetOutputPort());
  tumour_actor_->SetMapper(tm);
  tumour_actor_->GetProperty()->SetColor(0.85, 0.1, 0.15);
  tumour_actor_->GetProperty()->SetOpacity(0.85);
  tumour_actor_->PickableOff();
  renderer_->AddActor(tumour_actor_);

  // The chest (static): a slab under the breast's base.
  vtkNew<vtkCubeSource> chest;
  chest->SetCenter(0.06, 0.0, -0.0068);  // top 0.8 mm below the base: no z-fighting with it
  chest->SetXLength(0.42);
  chest->SetYLength(0.34);
  chest->SetZLength(0.012);
  vtkNew<vtkPolyDataMapper> cm;
  cm->SetInputConnection(chest->GetOutputPort());
  chest_actor_->SetMapper(cm);
  chest_actor_->GetProperty()->SetColor(0.62, 0.50, 0.46);
  chest_actor_->PickableOff();
  renderer_->AddActor(chest_actor_);

  for (int f = 0; f < 5; ++f) {
    vtkNew<vtkSphereSource> s;
    s->SetRadius(1.0);
    s->SetThetaResolution(24);
    s->SetPhiResolution(16);
    vtkNew<vtkPolyDataMapper> m;
    m->SetInputConnection(s->GetOutputPort());
    auto a = vtkSmartPointer<vtkActor>::New();
    a->SetMapper(m);
    a->GetProperty()->SetColor(kFingerColour[f][0], kFingerColour[f][1], kFingerColour[f][2]);
    a->SetScale(0.008);
    a->VisibilityOff();
    a->PickableOff();
    renderer_->AddActor(a);
    finger_actors_.push_back(a);
  }

  overlay_->GetTextProperty()->SetFontSize(16);
  overlay_->GetTextProperty()->SetColor(1, 1, 1);
  overlay_->SetDisplayPosition(12, 12);
  renderer_->AddActor2D(overlay_);

  picker_->SetTolerance(0.0005);
  picker_->PickFromListOn();
  picker_->AddPickList(surface_actor_);
  set_camera(CameraPreset::Oblique);
}

VtkView::~VtkView() {
  makeCurrent();
  window_->Finalize();
  doneCurrent();
}

void VtkView::initializeGL() {
  window_->SetOwnContext(false);
  window_->SetReadyForRendering(true);
  window_->OpenGLInitContext();
  initialized_ = true;
  if (stereo_ != Stereo::Mono) set_stereo(stereo_);
}

void VtkView::resizeGL(int w, int h) {
  const qreal r = devicePixelRatioF();
  window_->SetSize(int(w * r), int(h * r));
  interactor_->UpdateSize(int(w * r), int(h * r));
}

void VtkView::paintGL() {
  if (!initialized_) return;
  vtkOpenGLState* st = window_->GetState();
  st->Reset();
  st->Push();
  st->vtkglDepthFunc(GL_LEQUAL);
  window_->Render();
  // Blit VTK's display framebuffer into the widget's (mirrored for the half mirror).
  const qreal r = devicePixelRatioF();
  const int w = int(width() * r), h = int(height() * r);
  st->PushDrawFramebufferBinding();
  st->vtkglBindFramebuffer(GL_DRAW_FRAMEBUFFER, defaultFramebufferObject());
  st->vtkglViewport(0, 0, w, h);
  st->vtkglScissor(0, 0, w, h);
  if (mirrored_) window_->BlitDisplayFramebuffer(0, 0, 0, w, h, w, 0, -w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  else window_->BlitDisplayFramebuffer(0, 0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  // Alpha to 1 (the widget is composited with its alpha).
  st->vtkglColorMask(false, false, false, true);
  st->vtkglClearColor(0, 0, 0, 1);
  st->vtkglClear(GL_COLOR_BUFFER_BIT);
  st->vtkglColorMask(true, true, true, true);
  st->PopDrawFramebufferBinding();
  st->Pop();
  ++frames_;
}

void VtkView::set_patient(std::shared_ptr<const app::PatientGeometry> g) {
  geometry_ = std::move(g);
  if (!geometry_) return;
  const auto& rest = geometry_->rest;
  points_->SetDataTypeToFloat();
  points_->SetNumberOfPoints(vtkIdType(rest.size()));
  for (std::size_t i = 0; i < rest.size(); ++i) points_->SetPoint(vtkIdType(i), rest[i].x(), rest[i].y(), rest[i].z());
  points_->Modified();
  vtkNew<vtkCellArray> tris;
  for (const auto& t : geometry_->surface) {
    const vtkIdType ids[3] = {t[0], t[1], t[2]};
    tris->InsertNextCell(3, ids);
  }
  surface_->SetPolys(tris);
  displacement_->SetNumberOfTuples(vtkIdType(rest.size()));
  displacement_->Fill(0.0);
  surface_->GetPointData()->SetScalars(displacement_);
  surface_->Modified();
  set_element_young(geometry_->young);
  update();
}

void VtkView::show_snapshot(const app::RenderSnapshot& s) {
  if (geometry_ && s.model_generation == geometry_->generation && s.positions.size() == geometry_->rest.size() * 3) {
    const auto& rest = geometry_->rest;
    float* p = static_cast<float*>(points_->GetVoidPointer(0));
    std::copy(s.positions.begin(), s.positions.end(), p);
    for (std::size_t i = 0; i < rest.size(); ++i) {
      const double dx = s.positions[3 * i] - rest[i].x(), dy = s.positions[3 * i + 1] - rest[i].y(),
                   dz = s.positions[3 * i + 2] - rest[i].z();
      displacement_->SetValue(vtkIdType(i), float(std::sqrt(dx * dx + dy * dy + dz * dz)));
    }
    points_->Modified();
    displacement_->Modified();
    surface_->Modified();
    tumour_grid_->Modified();
  }
  for (int f = 0; f < 5; ++f) {
    auto& a = finger_actors_[f];
    a->SetVisibility(s.finger_active[f]);
    a->SetPosition(s.finger_position[f].x(), s.finger_position[f].y(), s.finger_position[f].z());
    a->SetScale(s.finger_radius);
  }
  update();
}

void VtkView::set_element_young(const std::vector<double>& young) {
  young_ = young;
  tumour_grid_->Reset();
  tumour_grid_->SetPoints(points_);
  if (!geometry_) return;
  tumour_grid_->Allocate(64);
  const double threshold = geometry_->tissue_young * 1.2;
  for (std::size_t e = 0; e < young.size() && e < geometry_->tets.size(); ++e) {
    if (young[e] <= threshold) continue;
    const auto& t = geometry_->tets[e];
    const vtkIdType ids[4] = {t[0], t[1], t[2], t[3]};
    tumour_grid_->InsertNextCell(VTK_TETRA, 4, ids);
  }
  tumour_grid_->Modified();
  update();
}

int VtkView::tumour_cell_count() const { return int(tumour_grid_->GetNumberOfCells()); }

void VtkView::set_tumours_visible(bool on) {
  tumours_visible_ = on;
  tumour_actor_->SetVisibility(on);
  // Instructors see the tumours through a translucent skin; trainees see opaque skin.
  surface_actor_->GetProperty()->SetOpacity(on ? 0.6 : 1.0);
  update();
}

void VtkView::set_colour_map(bool on) {
  colour_map_ = on;
  surface_actor_->GetMapper()->SetScalarVisibility(on);
  update();
}

bool VtkView::set_stereo(Stereo mode, QString* why) {
  if (mode == Stereo::QuadBuffer) {
    // Qt 6.4's QOpenGLWidget has no stereo buffers (stack-notes.md); a context with
    // stereo would have to come from a QOpenGLWindow where the driver grants it.
    const bool granted = context() && context()->format().stereo();
    if (!granted) {
      if (why)
        *why = tr("Quad-buffer stereo is not available: this display's OpenGL context has no stereo buffers "
                  "(needs a stereo-capable GPU, driver and display). Use anaglyph, side-by-side or interlaced.");
      return false;
    }
  }
  stereo_ = mode;
  switch (mode) {
    case Stereo::Mono: window_->SetStereoRender(0); break;
    case Stereo::Anaglyph:
      window_->SetStereoTypeToAnaglyph();
      window_->SetStereoRender(1);
      break;
    case Stereo::SideBySide:
      window_->SetStereoTypeToSplitViewportHorizontal();
      window_->SetStereoRender(1);
      break;
    case Stereo::Interlaced:
      window_->SetStereoTypeToInterlaced();
      window_->SetStereoRender(1);
      break;
    case Stereo::QuadBuffer:
      window_->SetStereoTypeToCrystalEyes();
      window_->SetStereoRender(1);
      break;
  }
  update();
  return true;
}

void VtkView::set_eye_angle(double degrees) {
  renderer_->GetActiveCamera()->SetEyeAngle(degrees);
  update();
}

void VtkView::set_mirrored(bool on) {
  mirrored_ = on;
  update();
}

void VtkView::set_camera(CameraPreset p) {
  vtkCamera* c = renderer_->GetActiveCamera();
  const double cx = 0.125, cz = 0.035;
  c->SetFocalPoint(cx, 0.0, cz);
  switch (p) {
    case CameraPreset::Oblique:
      c->SetPosition(cx - 0.07, -0.40, 0.30);
      c->SetViewUp(0, 0, 1);
      break;
    case CameraPreset::Top:
      c->SetPosition(cx, 0.0, 0.40);
      c->SetViewUp(0, 1, 0);
      break;
    case CameraPreset::Side:
      c->SetPosition(cx, -0.40, 0.04);
      c->SetViewUp(0, 0, 1);
      break;
    case CameraPreset::Front:
      c->SetPosition(cx - 0.40, 0.0, 0.06);
      c->SetViewUp(0, 0, 1);
      break;
  }
  c->SetViewAngle(30);
  renderer_->ResetCameraClippingRange();
  update();
}

void VtkView::set_overlay_text(const QString& text) {
  overlay_->SetInput(text.toUtf8().constData());
  update();
}

bool VtkView::pick_surface(const QPoint& pos, Eigen::Vector3d& point, Eigen::Vector3d& normal) {
  if (!geometry_) return false;
  const qreal r = devicePixelRatioF();
  int x = int(pos.x() * r);
  const int y = int((height() - pos.y() - 1) * r);
  if (mirrored_) x = int(width() * r) - 1 - x;
  if (!picker_->Pick(x, y, 0, renderer_)) return false;
  if (picker_->GetActor() != surface_actor_.Get()) return false;
  double p[3], n[3];
  picker_->GetPickPosition(p);
  picker_->GetPickNormal(n);
  point = Eigen::Vector3d(p[0], p[1], p[2]);
  normal = Eigen::Vector3d(n[0], n[1], n[2]);
  if (normal.norm() < 1e-9) normal = Eigen::Vector3d::UnitZ();
  normal.normalize();
  return true;
}

void VtkView::forward_mouse(QMouseEvent* e, unsigned long vtk_event) {
  const qreal r = devicePixelRatioF();
  interactor_->SetEventInformationFlipY(int(e->position().x() * r), int(e->position().y() * r),
                                        (e->modifiers() & Qt::ControlModifier) ? 1 : 0,
                                        (e->modifiers() & Qt::ShiftModifier) ? 1 : 0);
  interactor_->InvokeEvent(vtk_event, e);
  update();
}

void VtkView::palpate_at(const QPoint& pos) {
  Eigen::Vector3d p, n;
  if (!pick_surface(pos, p, n)) {
    emit palpateTarget(Eigen::Vector3d::Zero(), false);
    return;
  }
  // The fingertip touches the skin at the cursor, pressed in by press_ along -n.
  const double radius = 0.008;
  emit palpateTarget(p + n * (radius - press_), true);
}

void VtkView::mousePressEvent(QMouseEvent* e) {
  last_pos_ = e->position().toPoint();
  if ((tool_ == Tool::Paint || tool_ == Tool::Erase) && e->button() == Qt::LeftButton) {
    Eigen::Vector3d p, n;
    stroke_ = true;
    if (pick_surface(last_pos_, p, n)) emit brushDab(p, n, true);
    else emit brushDab(Eigen::Vector3d::Constant(1e9), Eigen::Vector3d::UnitZ(), true);
    return;
  }
  if (tool_ == Tool::Palpate && e->button() == Qt::LeftButton) {
    pressing_ = true;
    return;
  }
  if (e->button() == Qt::LeftButton) forward_mouse(e, vtkCommand::LeftButtonPressEvent);
  else if (e->button() == Qt::RightButton) forward_mouse(e, vtkCommand::RightButtonPressEvent);
  else if (e->button() == Qt::MiddleButton) forward_mouse(e, vtkCommand::MiddleButtonPressEvent);
}

void VtkView::mouseMoveEvent(QMouseEvent* e) {
  const QPoint pos = e->position().toPoint();
  if (stroke_) {
    Eigen::Vector3d p, n;
    if (pick_surface(pos, p, n)) emit brushDab(p, n, false);
    last_pos_ = pos;
    return;
  }
  if (tool_ == Tool::Palpate) {
    if (pressing_) {  // dragging down presses deeper, up releases
      press_ = std::clamp(press_ + 0.0002 * (pos.y() - last_pos_.y()), 0.0, 0.03);
      palpate_at(last_pos_);
      last_pos_ = QPoint(last_pos_.x(), pos.y());
      return;
    }
    palpate_at(pos);
    last_pos_ = pos;
    if (!(e->buttons() & (Qt::RightButton | Qt::MiddleButton))) return;
  }
  last_pos_ = pos;
  forward_mouse(e, vtkCommand::MouseMoveEvent);
}

void VtkView::mouseReleaseEvent(QMouseEvent* e) {
  if (stroke_ && e->button() == Qt::LeftButton) {
    stroke_ = false;
    emit brushStrokeEnded();
    return;
  }
  if (pressing_ && e->button() == Qt::LeftButton) {
    pressing_ = false;
    return;
  }
  if (e->button() == Qt::LeftButton) forward_mouse(e, vtkCommand::LeftButtonReleaseEvent);
  else if (e->button() == Qt::RightButton) forward_mouse(e, vtkCommand::RightButtonReleaseEvent);
  else if (e->button() == Qt::MiddleButton) forward_mouse(e, vtkCommand::MiddleButtonReleaseEvent);
}

void VtkView::wheelEvent(QWheelEvent* e) {
  if (tool_ == Tool::Palpate) {
    press_ = std::clamp(press_ + (e->angleDelta().y() > 0 ? 0.001 : -0.001), 0.0, 0.03);
    palpate_at(e->position().toPoint());
    return;
  }
  const qreal r = devicePixelRatioF();
  interactor_->SetEventInformationFlipY(int(e->position().x() * r), int(e->position().y() * r));
  interactor_->InvokeEvent(e->angleDelta().y() > 0 ? vtkCommand::MouseWheelForwardEvent : vtkCommand::MouseWheelBackwardEvent, e);
  update();
}

void VtkView::leaveEvent(QEvent*) {
  if (tool_ == Tool::Palpate) emit palpateTarget(Eigen::Vector3d::Zero(), false);
}

}  // namespace palpation::ui
