#include "vtk_view.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <QCoreApplication>
#include <QElapsedTimer>
#include <QGuiApplication>
#include <QMouseEvent>
#include <QOffscreenSurface>
#include <QScopeGuard>
#include <QOpenGLContext>
#include <QOpenGLExtraFunctions>
#include <QOpenGLFunctions>
#include <QOpenGLWindow>
#include <QPainter>
#include <QResizeEvent>
#include <QWheelEvent>
#include <QSurfaceFormat>
#include <QWindow>

#include <vtkActor.h>
#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellPicker.h>
#include <vtkCubeSource.h>
#include <vtkFloatArray.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkGenericRenderWindowInteractor.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkLookupTable.h>
#include <vtkObjectFactory.h>
#include <vtkOpenGLActor.h>
#include <vtkOpenGLState.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkOpenGLFramebufferObject.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkTextureObject.h>
#include <vtkSphereSource.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkCellData.h>
#include <vtkUnsignedCharArray.h>

namespace palpation::ui {

namespace {

/// Triangles (node indices of the patient's mesh) as VTK polygon cells.
vtkSmartPointer<vtkCellArray> triangle_cells(const std::vector<std::array<int, 3>>& tris) {
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  cells->AllocateExact(vtkIdType(tris.size()), vtkIdType(tris.size() * 3));
  for (const auto& t : tris) {
    const vtkIdType ids[3] = {t[0], t[1], t[2]};
    cells->InsertNextCell(3, ids);
  }
  return cells;
}

// Fingertip colours (HandHIRO order: thumb, index, middle, ring, little).
const double kFingerColour[5][3] = {{0.95, 0.75, 0.2}, {0.2, 0.55, 0.95}, {0.3, 0.8, 0.4}, {0.75, 0.45, 0.9}, {0.9, 0.4, 0.5}};

// The translucent skin, drawn in VTK's opaque pass with plain alpha blending (VTK keeps
// GL_BLEND on, source alpha over), added to the renderer after every other 3-D actor so
// that the tumour, the chest and the fingertips are already in the framebuffer under it.
// Its front faces only (back-face culling) of a closed shell: each pixel gets one skin
// layer, so no depth sorting is needed. VTK 9.1 would otherwise draw any actor with
// opacity < 1 in its order-independent translucency pass (float accumulation targets and a
// full-screen composite), which under software GL doubled the view's render time (docs/gui.md).
class BlendedSkinActor : public vtkOpenGLActor {
 public:
  static BlendedSkinActor* New();
  vtkTypeMacro(BlendedSkinActor, vtkOpenGLActor)
  vtkTypeBool HasTranslucentPolygonalGeometry() override { return 0; }
  vtkTypeBool HasOpaqueGeometry() override { return GetVisibility() ? 1 : 0; }
};
vtkStandardNewMacro(BlendedSkinActor)
}  // namespace

// The native child window the view presents in (docs/gui.md). Exposure and update requests
// draw a frame; mouse, wheel and leave events go on to the view's handlers (picking,
// palpation, the tumour brush, the camera) at the same positions, the window filling the
// view. Keyboard focus stays with the widgets, so the window's shortcuts keep working; a
// click focuses the view.
class ViewWindow : public QWindow {
 public:
  explicit ViewWindow(VtkView* view) : view_(view) {
    setSurfaceType(QSurface::OpenGLSurface);
    setFormat(QSurfaceFormat::defaultFormat());
    setFlag(Qt::WindowDoesNotAcceptFocus);
  }
  void detach() { view_ = nullptr; }
  // Hands an event of the view's native window (this one or the quad-buffer window) to the
  // view, as if it had happened on the view; true when it was one of those.
  static bool forward(VtkView* view, QEvent* e) {
    switch (e->type()) {
      case QEvent::MouseButtonPress:
      case QEvent::MouseButtonDblClick:
        if (view->focusPolicy() & Qt::ClickFocus) view->setFocus(Qt::MouseFocusReason);
        [[fallthrough]];
      case QEvent::MouseButtonRelease:
      case QEvent::MouseMove:
      case QEvent::Wheel:
      case QEvent::Leave:
        QCoreApplication::sendEvent(view, e);
        return true;
      default: return false;
    }
  }

 protected:
  void exposeEvent(QExposeEvent*) override {
    if (view_ && isExposed()) view_->present();
  }
  bool event(QEvent* e) override {
    if (!view_) return QWindow::event(e);
    if (e->type() == QEvent::UpdateRequest) {
      view_->present();
      return true;
    }
    return forward(view_, e) || QWindow::event(e);
  }

 private:
  VtkView* view_;
};

VtkView::VtkView(QWidget* parent)
    : QWidget(parent),
      surface_actor_(vtkSmartPointer<BlendedSkinActor>::New()),
      layer_actor_(vtkSmartPointer<BlendedSkinActor>::New()) {
  setMouseTracking(true);
  setFocusPolicy(Qt::StrongFocus);
  setMinimumSize(320, 240);
  // The native window VTK presents in, filling this widget (docs/gui.md: only its pixels
  // are drawn with OpenGL; the rest of the window stays raster).
  gl_window_ = new ViewWindow(this);
  container_ = QWidget::createWindowContainer(gl_window_, this);
  container_->setMouseTracking(true);
  container_->setFocusPolicy(Qt::NoFocus);
  container_->setGeometry(rect());
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
    static_cast<VtkView*>(self)->make_current();
  });
  window_->AddObserver(vtkCommand::WindowMakeCurrentEvent, make_current);
  auto is_current = vtkSmartPointer<vtkCallbackCommand>::New();
  is_current->SetClientData(this);
  is_current->SetCallback([](vtkObject*, unsigned long, void* self, void* call_data) {
    auto* w = static_cast<VtkView*>(self);
    *static_cast<bool*>(call_data) = w->context_ && QOpenGLContext::currentContext() == w->context_;
  });
  window_->AddObserver(vtkCommand::WindowIsCurrentEvent, is_current);
  auto frame = vtkSmartPointer<vtkCallbackCommand>::New();
  frame->SetClientData(this);
  // A render VTK starts itself (not from present()) needs a frame; one inside present() must
  // not schedule another, or the view re-renders continuously (it did: 7-13 fps of
  // back-to-back frames under llvmpipe, taking CPU from the simulation).
  frame->SetCallback([](vtkObject*, unsigned long, void* self, void*) {
    auto* w = static_cast<VtkView*>(self);
    if (!w->painting_) w->request_render();
  });
  window_->AddObserver(vtkCommand::WindowFrameEvent, frame);

  renderer_->SetBackground(0.13, 0.15, 0.19);
  renderer_->SetBackground2(0.32, 0.36, 0.44);
  renderer_->GradientBackgroundOn();

  // Breast surface: all nodes as points (the snapshot's layout, updated in place), the
  // surface triangles as cells, point normals computed here (update_normals), no filter.
  surface_->SetPoints(points_);
  normals_->SetName("normals");
  normals_->SetNumberOfComponents(3);
  surface_->GetPointData()->SetNormals(normals_);
  scalars_->SetName("colour");
  surface_->GetPointData()->SetScalars(scalars_);
  vtkNew<vtkPolyDataMapper> sm;
  sm->SetInputData(surface_);
  sm->ScalarVisibilityOff();
  sm->SetColorModeToMapScalars();
  sm->InterpolateScalarsBeforeMappingOn();
  lut_->SetHueRange(0.66, 0.0);
  lut_->Build();
  sm->SetLookupTable(lut_);
  sm->UseLookupTableScalarRangeOn();
  lut_->SetTableRange(0.0, 15.0);
  surface_actor_->SetMapper(sm);
  surface_actor_->GetProperty()->SetColor(0.96, 0.80, 0.70);
  surface_actor_->GetProperty()->SetSpecular(0.2);
  surface_actor_->GetProperty()->SetSpecularPower(20);
  surface_actor_->GetProperty()->SetOpacity(0.6);
  // Only the skin's front faces: with the tumour opaque under it, plain alpha blending
  // of a convex shell needs no depth sorting (no depth peeling, a single pass; drawn in
  // the opaque pass, last: BlendedSkinActor).
  surface_actor_->GetProperty()->BackfaceCullingOn();

  scalar_bar_->SetLookupTable(lut_);
  scalar_bar_->SetNumberOfLabels(4);
  scalar_bar_->SetLabelFormat("%.3g");
  scalar_bar_->SetMaximumWidthInPixels(90);
  scalar_bar_->SetMaximumHeightInPixels(260);
  scalar_bar_->SetPosition(0.86, 0.08);
  scalar_bar_->SetWidth(0.12);
  scalar_bar_->SetHeight(0.5);
  scalar_bar_->GetTitleTextProperty()->SetFontSize(12);
  scalar_bar_->GetLabelTextProperty()->SetFontSize(11);
  scalar_bar_->VisibilityOff();
  renderer_->AddActor2D(scalar_bar_);

  // Tumours: the boundary faces of the stiff elements, sharing the deformed points;
  // opaque, flat-shaded from the fragment derivatives (no normals to update).
  tumour_poly_->SetPoints(points_);
  vtkNew<vtkPolyDataMapper> tm;
  tm->SetInputData(tumour_poly_);
  tm->ScalarVisibilityOff();
  tumour_actor_->SetMapper(tm);
  tumour_actor_->GetProperty()->SetColor(0.85, 0.1, 0.15);
  tumour_actor_->PickableOff();
  renderer_->AddActor(tumour_actor_);

  // The deeper tissue layer (glandular under the fat): its boundary inside the breast, on
  // the same deformed points, translucent so that the tumours inside it show. Blended in
  // the opaque pass like the skin (a translucent-pass actor would come after the skin and
  // fail the depth test behind it), before the skin and after the tumours.
  layer_poly_->SetPoints(points_);
  vtkNew<vtkPolyDataMapper> lm;
  lm->SetInputData(layer_poly_);
  lm->ScalarVisibilityOff();
  layer_actor_->SetMapper(lm);
  // Pink-violet: a hue the skin tone does not hide, with little green, so that the red of
  // a tumour seen through it stays red.
  layer_actor_->GetProperty()->SetColor(0.85, 0.5, 0.8);
  layer_actor_->GetProperty()->SetOpacity(0.3);
  layer_actor_->PickableOff();
  renderer_->AddActor(layer_actor_);

  // The coverage overlay: the surface's triangles on the same deformed points and normals,
  // one colour per face (cell scalars, direct RGB), pulled towards the camera so that it
  // wins the depth test over the skin under it (the translucent skin does not tint it).
  coverage_poly_->SetPoints(points_);
  coverage_poly_->GetPointData()->SetNormals(normals_);
  vtkNew<vtkPolyDataMapper> covm;
  covm->SetInputData(coverage_poly_);
  covm->SetScalarModeToUseCellData();
  covm->SetColorModeToDirectScalars();
  covm->ScalarVisibilityOn();
  covm->SetResolveCoincidentTopologyToPolygonOffset();
  covm->SetRelativeCoincidentTopologyPolygonOffsetParameters(-2.0, -8.0);
  coverage_actor_->SetMapper(covm);
  coverage_actor_->GetProperty()->BackfaceCullingOn();
  coverage_actor_->GetProperty()->SetSpecular(0.0);
  coverage_actor_->PickableOff();
  coverage_actor_->VisibilityOff();
  renderer_->AddActor(coverage_actor_);

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
  renderer_->AddActor(surface_actor_);  // last: blended over the others (BlendedSkinActor)

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
  delete quad_container_;  // deletes the stereo window
  quad_container_ = nullptr;
  quad_window_ = nullptr;
  if (initialized_ && make_current()) {
    window_->Finalize();
    done_current();
  }
  initialized_ = false;
  // The native window outlives this body (a child): it must not call back into the view.
  if (gl_window_) gl_window_->detach();
  delete container_;  // deletes the native window
  container_ = nullptr;
  gl_window_ = nullptr;
  delete context_;
  context_ = nullptr;
}

bool VtkView::ensure_gl() {
  if (initialized_) return true;
  if (!gl_window_ || !gl_window_->handle()) return false;  // not created yet (never shown)
  if (!context_) {
    context_ = new QOpenGLContext;
    context_->setFormat(gl_window_->requestedFormat());
    if (!context_->create()) {
      static bool said = false;  // once, not per frame (the offscreen platform without a display has none)
      if (!std::exchange(said, true)) qWarning("palpation: no OpenGL context for the 3-D view");
      delete context_;
      context_ = nullptr;
      return false;
    }
  }
  if (!context_->makeCurrent(gl_window_)) return false;
  window_->SetOwnContext(false);
  window_->SetReadyForRendering(true);
  window_->OpenGLInitContext();
  initialized_ = true;
  // The renderer, once: software OpenGL gets the light style (Auto).
  if (const auto* name = context_->functions()->glGetString(GL_RENDERER))
    gl_renderer_ = QString::fromLatin1(reinterpret_cast<const char*>(name));
  software_ = is_software_renderer(gl_renderer_);
  apply_style();
  if (stereo_ != Stereo::Mono) set_stereo(stereo_);
  return true;
}

bool VtkView::is_software_renderer(const QString& r) {
  for (const char* s : {"llvmpipe", "softpipe", "swrast", "Software"})
    if (r.contains(QLatin1String(s), Qt::CaseInsensitive)) return true;
  return false;
}

void VtkView::set_render_style(RenderStyle s) {
  style_ = s;
  apply_style();
}

void VtkView::apply_style() {
  const bool light = style_ == RenderStyle::Light || (style_ == RenderStyle::Auto && software_);
  // docs/gui.md (measured under llvmpipe): the gradient background is a full-view shaded
  // quad, the skin's specular term half of its shading, the lit chest slab about half the
  // view's pixels. The light style drops them: a plain clear, diffuse skin, an unlit chest.
  renderer_->SetGradientBackground(!light);
  if (light) renderer_->SetBackground(0.2, 0.23, 0.29);  // between the gradient's ends
  else renderer_->SetBackground(0.13, 0.15, 0.19);
  surface_actor_->GetProperty()->SetSpecular(light ? 0.0 : 0.2);
  // Unlit, the chest would show its full colour, as bright as the skin: the colour it has
  // lit from the oblique camera's headlight (about 0.55 of it) instead.
  chest_actor_->GetProperty()->SetLighting(!light);
  if (light) chest_actor_->GetProperty()->SetColor(0.34, 0.275, 0.25);
  else chest_actor_->GetProperty()->SetColor(0.62, 0.50, 0.46);
  const bool changed = light != light_;
  light_ = light;
  request_render();
  if (changed) emit lightStyleChanged(light);
}

bool VtkView::make_current() {
  return context_ && gl_window_ && gl_window_->handle() && context_->makeCurrent(gl_window_);
}

void VtkView::done_current() {
  if (context_) context_->doneCurrent();
}

QWindow* VtkView::native_window() const { return gl_window_; }

void VtkView::resizeEvent(QResizeEvent* e) {
  QWidget::resizeEvent(e);
  container_->setGeometry(rect());
  if (quad_container_) quad_container_->setGeometry(rect());
  const qreal r = devicePixelRatioF();
  window_->SetSize(int(width() * r), int(height() * r));
  interactor_->UpdateSize(int(width() * r), int(height() * r));
  request_render();
}

bool VtkView::event(QEvent* e) {
  // The pointer over the view is over the native window: it takes the view's cursor.
  if (e->type() == QEvent::CursorChange && gl_window_) gl_window_->setCursor(cursor());
  return QWidget::event(e);
}

void VtkView::request_render() {
  if (gl_window_) gl_window_->requestUpdate();
}

void VtkView::render_vtk() {
  painting_ = true;
  const auto done = qScopeGuard([this] { painting_ = false; });
  vtkOpenGLState* st = window_->GetState();
  st->Reset();
  st->Push();
  st->vtkglDepthFunc(GL_LEQUAL);
  window_->Render();
  st->Pop();
}

void VtkView::present() {
  if (!gl_window_ || !gl_window_->isExposed()) {
    pending_ = true;  // drawn when the window is exposed
    return;
  }
  if (!ensure_gl()) return;
  pending_ = false;
  if (quad_window_) {  // quad-buffer stereo: the stereo window renders and presents
    quad_window_->requestUpdate();
    return;
  }
  QElapsedTimer timer;
  timer.start();
  if (!make_current()) return;
  render_vtk();
  const qint64 rendered = timer.nsecsElapsed();
  // Blit VTK's display framebuffer into the window's back buffer (mirrored for the half
  // mirror) and swap: only the view's pixels go to the display.
  vtkOpenGLState* st = window_->GetState();
  st->Reset();
  st->Push();
  const qreal r = devicePixelRatioF();
  const int w = int(width() * r), h = int(height() * r);
  st->PushDrawFramebufferBinding();
  st->vtkglBindFramebuffer(GL_DRAW_FRAMEBUFFER, context_->defaultFramebufferObject());
  st->vtkglViewport(0, 0, w, h);
  st->vtkglScissor(0, 0, w, h);
  if (mirrored_) window_->BlitDisplayFramebuffer(0, 0, 0, w, h, w, 0, -w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  else window_->BlitDisplayFramebuffer(0, 0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  st->PopDrawFramebufferBinding();
  st->Pop();
  const qint64 blitted = timer.nsecsElapsed();
  context_->swapBuffers(gl_window_);
  ++frames_;
  const qint64 end = timer.nsecsElapsed();
  paint_ns_ += double(end);
  render_ns_ += double(rendered);
  swap_ns_ += double(end - blitted);
}

bool VtkView::render_now() {
  if (!gl_window_ || !gl_window_->isExposed() || !ensure_gl()) return false;
  present();
  return true;
}

double VtkView::bench_render(int n) {
  if (n <= 0 || !ensure_gl() || !make_current()) return 0;
  QElapsedTimer t;
  t.start();
  for (int i = 0; i < n; ++i) {
    render_vtk();
    context_->functions()->glFinish();
  }
  return double(t.nsecsElapsed()) * 1e-6 / n;
}

QImage VtkView::grabFramebuffer() {
  if (!ensure_gl() || !make_current()) return {};
  render_vtk();
  vtkOpenGLFramebufferObject* display = window_->GetDisplayFramebuffer();
  if (!display) return {};
  const qreal r = devicePixelRatioF();
  const int w = int(width() * r), h = int(height() * r);
  QImage img(w, h, QImage::Format_RGBA8888);
  vtkOpenGLState* st = window_->GetState();
  st->Reset();
  st->Push();
  st->PushReadFramebufferBinding();
  display->Bind(GL_READ_FRAMEBUFFER);
  display->ActivateReadBuffer(0);  // the left eye in quad-buffer stereo
  QOpenGLFunctions* f = context_->functions();
  f->glPixelStorei(GL_PACK_ALIGNMENT, 4);
  f->glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, img.bits());
  st->PopReadFramebufferBinding();
  st->Pop();
  // OpenGL's rows run bottom-up; the half mirror flips left and right as shown.
  img = img.mirrored(mirrored_, true).convertToFormat(QImage::Format_RGB32);
  img.setDevicePixelRatio(r);
  return img;
}

QImage VtkView::grab_with_views(QWidget* w) {
  QImage img = w->grab().toImage();
  if (img.isNull()) return img;
  QList<VtkView*> views = w->findChildren<VtkView*>();
  if (auto* self = qobject_cast<VtkView*>(w)) views.prepend(self);
  QPainter p(&img);
  for (VtkView* v : views) {
    // Only views shown inside w (not those of other top-level windows w happens to own).
    if (v != w && (!v->isVisible() || v->window() != w->window() || !w->isAncestorOf(v))) continue;
    const QImage frame = v->grabFramebuffer();
    if (frame.isNull()) continue;
    p.drawImage(QRect(v == w ? QPoint() : v->mapTo(w, QPoint()), v->size()), frame);
  }
  return img;
}

// ---------------------------------------------------------------------------------------
// Quad-buffer stereo. The view's window has the default (mono) format, fixed when it is
// created, and the stereo format is asked for only where granted (stack-notes.md), so a
// second native window with a stereo format, sharing objects with the view's context,
// covers the view: VTK renders both eyes (CrystalEyes) in the view's context into the two colour
// textures of its display framebuffer; this window blits them into GL_BACK_LEFT and
// GL_BACK_RIGHT of its own default framebuffer. Mouse and wheel events go on to the view.

namespace {
QSurfaceFormat stereo_format() {
  QSurfaceFormat f = QSurfaceFormat::defaultFormat();
  f.setStereo(true);
  return f;
}
}  // namespace

class QuadBufferWindow : public QOpenGLWindow {
 public:
  explicit QuadBufferWindow(VtkView* view) : QOpenGLWindow(view->context_, QOpenGLWindow::NoPartialUpdate), view_(view) {
    setFormat(stereo_format());
  }
  ~QuadBufferWindow() override {
    if (fbo_ && context()) {
      makeCurrent();
      context()->extraFunctions()->glDeleteFramebuffers(1, &fbo_);
      doneCurrent();
    }
  }

 protected:
  void paintGL() override {
    QElapsedTimer timer;
    timer.start();
    // 1. Both eyes, in the view's context.
    if (!view_->make_current()) return;
    view_->render_vtk();
    vtkOpenGLFramebufferObject* display = view_->window_->GetDisplayFramebuffer();
    vtkTextureObject* lt = display ? display->GetColorAttachmentAsTextureObject(0) : nullptr;
    vtkTextureObject* rt = display ? display->GetColorAttachmentAsTextureObject(1) : nullptr;
    const GLuint left = lt ? lt->GetHandle() : 0, right = rt ? rt->GetHandle() : left;
    view_->context_->functions()->glFinish();
    view_->done_current();
    // 2. Into the stereo back buffers, in this window's context.
    makeCurrent();
    if (!left) return;
    QOpenGLExtraFunctions* f = context()->extraFunctions();
    using DrawBuffer = void (*)(GLenum);
    auto draw_buffer = reinterpret_cast<DrawBuffer>(context()->getProcAddress("glDrawBuffer"));
    if (!fbo_) f->glGenFramebuffers(1, &fbo_);
    const qreal r = devicePixelRatio();
    const int w = int(width() * r), h = int(height() * r);
    f->glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo_);
    f->glBindFramebuffer(GL_DRAW_FRAMEBUFFER, defaultFramebufferObject());
    for (int eye = 0; eye < 2; ++eye) {
      f->glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, eye ? right : left, 0);
      f->glReadBuffer(GL_COLOR_ATTACHMENT0);
      if (draw_buffer) draw_buffer(eye ? GL_BACK_RIGHT : GL_BACK_LEFT);
      if (view_->mirrored_) f->glBlitFramebuffer(0, 0, w, h, w, 0, 0, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
      else f->glBlitFramebuffer(0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    }
    f->glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    ++view_->frames_;
    view_->paint_ns_ += double(timer.nsecsElapsed());
  }
  bool event(QEvent* e) override { return ViewWindow::forward(view_, e) || QOpenGLWindow::event(e); }

 private:
  VtkView* view_;
  GLuint fbo_ = 0;
};

void VtkView::use_default_surface_format() {
  QSurfaceFormat fmt;
  fmt.setRenderableType(QSurfaceFormat::OpenGL);
  fmt.setVersion(3, 2);
  fmt.setProfile(QSurfaceFormat::CoreProfile);
  fmt.setDepthBufferSize(24);
  fmt.setStencilBufferSize(8);
  fmt.setSwapInterval(0);
  QSurfaceFormat::setDefaultFormat(fmt);
}

bool VtkView::quad_buffer_available(QString* why) {
  static int granted = -1;
  static QString reason;
  if (granted < 0) {
    // A small native window with a stereo format and a context for it: whether the
    // platform chose a stereo visual/pixel format shows in the context's format.
    QWindow probe;
    probe.setSurfaceType(QSurface::OpenGLSurface);
    probe.setFormat(stereo_format());
    probe.resize(16, 16);
    probe.create();
    QOpenGLContext ctx;
    ctx.setFormat(stereo_format());
    if (!probe.handle() || !ctx.create()) {
      granted = 0;
      reason = tr("no OpenGL context for a native window on this platform (%1)").arg(QGuiApplication::platformName());
    } else if (!ctx.makeCurrent(&probe) || !ctx.format().stereo()) {
      granted = 0;
      reason = tr("the display's OpenGL (%1) has no stereo buffers; quad-buffer stereo needs a stereo-capable GPU, "
                  "driver and display").arg(QGuiApplication::platformName());
      ctx.doneCurrent();
    } else {
      granted = 1;
      ctx.doneCurrent();
    }
  }
  if (why) *why = reason;
  return granted == 1;
}

void VtkView::set_patient(std::shared_ptr<const app::live::PatientGeometry> g) {
  geometry_ = std::move(g);
  if (!geometry_) return;
  const auto& rest = geometry_->rest;
  points_->SetDataTypeToFloat();
  points_->SetNumberOfPoints(vtkIdType(rest.size()));
  for (std::size_t i = 0; i < rest.size(); ++i) points_->SetPoint(vtkIdType(i), rest[i].x(), rest[i].y(), rest[i].z());
  points_->Modified();
  const vtkSmartPointer<vtkCellArray> tris = triangle_cells(geometry_->surface);
  surface_->SetPolys(tris);
  coverage_poly_->SetPolys(tris);
  shown_levels_.assign(geometry_->surface.size(), 255);  // every face's colour is set below
  set_coverage(std::vector<unsigned char>(geometry_->surface.size(), 0));
  normals_->SetNumberOfTuples(vtkIdType(rest.size()));
  scalars_->SetNumberOfTuples(vtkIdType(rest.size()));
  scalars_->Fill(0.0);
  shown_positions_.clear();
  shown_stress_.clear();
  update_normals();
  surface_->Modified();
  tumour_poly_->SetPolys(vtkNew<vtkCellArray>());
  tumour_poly_->Modified();
  tumour_cells_ = 0;
  const auto layer = app::live::deep_layer_faces(*geometry_);
  layer_poly_->SetPolys(triangle_cells(layer));
  layer_poly_->Modified();
  layer_faces_ = int(layer.size());
  request_render();
}

void VtkView::update_normals() {
  // Area-weighted vertex normals of the surface triangles (outward): the cross product's
  // length is twice the area, so summing unnormalized face normals weights by area.
  if (!geometry_) return;
  const vtkIdType n = points_->GetNumberOfPoints();
  float* nrm = normals_->GetPointer(0);
  std::fill(nrm, nrm + 3 * n, 0.0f);
  const float* p = static_cast<const float*>(points_->GetVoidPointer(0));
  for (const auto& t : geometry_->surface) {
    const float* a = p + 3 * t[0];
    const float* b = p + 3 * t[1];
    const float* c = p + 3 * t[2];
    const float u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const float f[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < 3; ++j) nrm[3 * t[k] + j] += f[j];
  }
  for (vtkIdType i = 0; i < n; ++i) {
    float* q = nrm + 3 * i;
    const float l = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
    if (l > 0) {
      q[0] /= l;
      q[1] /= l;
      q[2] /= l;
    } else {
      q[2] = 1.0f;  // interior nodes: not drawn
    }
  }
  normals_->Modified();
}

void VtkView::update_scalars(const app::live::RenderSnapshot* s) {
  if (!geometry_ || colour_map_ == ColourMap::None) return;
  const auto& rest = geometry_->rest;
  float* out = scalars_->GetPointer(0);
  const float* p = static_cast<const float*>(points_->GetVoidPointer(0));
  if (colour_map_ == ColourMap::Displacement) {
    for (std::size_t i = 0; i < rest.size(); ++i) {
      const double dx = p[3 * i] - rest[i].x(), dy = p[3 * i + 1] - rest[i].y(), dz = p[3 * i + 2] - rest[i].z();
      out[i] = float(1000.0 * std::sqrt(dx * dx + dy * dy + dz * dz));  // mm
    }
  } else {
    const std::vector<float>* vm = s ? &s->von_mises : &shown_stress_;
    const bool have = vm->size() == rest.size();
    for (std::size_t i = 0; i < rest.size(); ++i) out[i] = have ? 1e-3f * (*vm)[i] : 0.0f;  // kPa
  }
  scalars_->Modified();
}

void VtkView::show_snapshot(const app::live::RenderSnapshot& s) {
  QElapsedTimer timer;
  timer.start();
  bool changed = false;
  if (geometry_ && s.model_generation == geometry_->generation && s.positions.size() == geometry_->rest.size() * 3) {
    const bool moved = shown_positions_ != s.positions;
    const bool stress = colour_map_ == ColourMap::Stress && shown_stress_ != s.von_mises;
    if (moved) {
      shown_positions_ = s.positions;
      float* p = static_cast<float*>(points_->GetVoidPointer(0));
      std::copy(s.positions.begin(), s.positions.end(), p);
      points_->Modified();
      update_normals();
    }
    if (stress) shown_stress_ = s.von_mises;
    if (moved || stress) update_scalars(&s);
    changed = moved || stress;
  }
  for (int f = 0; f < 5; ++f) {
    const bool active = s.finger_active[f];
    if (active == shown_active_[f] && (!active || s.finger_position[f] == shown_fingers_[f])) continue;
    shown_active_[f] = active;
    shown_fingers_[f] = s.finger_position[f];
    auto& a = finger_actors_[f];
    a->SetVisibility(active);
    a->SetPosition(s.finger_position[f].x(), s.finger_position[f].y(), s.finger_position[f].z());
    a->SetScale(s.finger_radius);
    changed = true;
  }
  ++snapshots_;
  update_ns_ += double(timer.nsecsElapsed());
  if (!changed) {
    ++skipped_;  // nothing moved: keep the last frame
    return;
  }
  request_render();
}

void VtkView::show_tumours(const app::live::TumourDocument& doc) {
  // The boundary of the tumour elements, once per material change.
  std::vector<std::array<int, 3>> tris;
  tumour_cells_ = 0;
  if (geometry_ && doc.patient() && doc.generation() == geometry_->generation) {
    tumour_cells_ = doc.tumour_element_count();
    tris = doc.tumour_faces();
  }
  tumour_poly_->SetPolys(triangle_cells(tris));
  tumour_poly_->Modified();
  request_render();
}

int VtkView::tumour_cell_count() const { return tumour_cells_; }

void VtkView::set_tumours_visible(bool on) {
  tumours_visible_ = on;
  tumour_actor_->SetVisibility(on);
  layer_actor_->SetVisibility(on);
  // Instructors see the tumours through a translucent skin; trainees see opaque skin.
  surface_actor_->GetProperty()->SetOpacity(on ? 0.6 : 1.0);
  request_render();
}

void VtkView::set_coverage(const std::vector<unsigned char>& levels) {
  if (!geometry_) return;
  const std::size_t n = geometry_->surface.size();
  auto* colours = vtkUnsignedCharArray::SafeDownCast(coverage_poly_->GetCellData()->GetScalars());
  if (!colours || colours->GetNumberOfTuples() != vtkIdType(n)) {
    auto c = vtkSmartPointer<vtkUnsignedCharArray>::New();
    c->SetName("coverage");
    c->SetNumberOfComponents(3);
    c->SetNumberOfTuples(vtkIdType(n));
    coverage_poly_->GetCellData()->SetScalars(c);
    colours = c;
    shown_levels_.assign(n, 255);
  }
  bool changed = false;
  coverage_counts_ = {};
  for (std::size_t i = 0; i < n; ++i) {
    const unsigned char l = i < levels.size() ? std::min<unsigned char>(levels[i], 3) : 0;
    ++coverage_counts_[l];
    if (shown_levels_[i] == l) continue;
    shown_levels_[i] = l;
    colours->SetTypedTuple(vtkIdType(i), kCoverageColour[l]);
    changed = true;
  }
  if (!changed) return;
  colours->Modified();
  coverage_poly_->Modified();
  if (coverage_visible_) request_render();
}

void VtkView::set_coverage_visible(bool on) {
  if (on == coverage_visible_) return;
  coverage_visible_ = on;
  coverage_actor_->SetVisibility(on);
  request_render();
}

void VtkView::set_colour_mode(ColourMap m) {
  colour_map_ = m;
  auto* mapper = surface_actor_->GetMapper();
  mapper->SetScalarVisibility(m != ColourMap::None);
  if (m == ColourMap::Displacement) {
    lut_->SetTableRange(0.0, 15.0);
    scalar_bar_->SetTitle("|u| mm");
  } else if (m == ColourMap::Stress) {
    // 0-10 kPa: the tissue (19 kPa) under a deep push reaches a few kPa; the tumour
    // (107 kPa) beneath the finger more (saturates red).
    lut_->SetTableRange(0.0, 10.0);
    scalar_bar_->SetTitle("von Mises kPa");
  }
  scalar_bar_->SetVisibility(m != ColourMap::None);
  update_scalars(nullptr);
  request_render();
}

bool VtkView::set_stereo(Stereo mode, QString* why) {
  bool ok = true;
  if (mode == Stereo::QuadBuffer) {
    QString reason;
    if (!quad_buffer_available(&reason) || !context_) {
      // Refused: say why and show anaglyph, which needs nothing of the display.
      if (why)
        *why = tr("Quad-buffer stereo is not available: %1. Showing anaglyph (red/cyan glasses) instead; "
                  "side-by-side and interlaced are also available.")
                   .arg(context_ ? reason : tr("the view is not initialised yet"));
      mode = Stereo::Anaglyph;
      ok = false;
    }
  }
  if (mode != Stereo::QuadBuffer && quad_container_) {
    delete quad_container_;  // deletes the stereo window
    quad_container_ = nullptr;
    quad_window_ = nullptr;
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
      if (!quad_window_) {
        quad_window_ = new QuadBufferWindow(this);
        quad_container_ = QWidget::createWindowContainer(quad_window_, this);
        quad_container_->setGeometry(rect());
        quad_container_->show();
        quad_container_->raise();  // over the mono window
      }
      break;
  }
  request_render();
  return ok;
}

void VtkView::set_eye_angle(double degrees) {
  renderer_->GetActiveCamera()->SetEyeAngle(degrees);
  request_render();
}

void VtkView::set_mirrored(bool on) {
  mirrored_ = on;
  request_render();
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
  request_render();
}

void VtkView::set_overlay_text(const QString& text) {
  // The main window sets the text 4 times a second; the same text again needs no frame
  // (an idle view drew 4 frames a second for it).
  const QByteArray utf8 = text.toUtf8();
  const char* shown = overlay_->GetInput();
  if (utf8 == QByteArray(shown ? shown : "")) return;
  overlay_->SetInput(utf8.constData());
  request_render();
}

std::optional<VtkView::SurfacePick> VtkView::pick_surface(const QPoint& pos) {
  if (!geometry_) return std::nullopt;
  const qreal r = devicePixelRatioF();
  int x = int(pos.x() * r);
  const int y = int((height() - pos.y() - 1) * r);
  if (mirrored_) x = int(width() * r) - 1 - x;
  if (!picker_->Pick(x, y, 0, renderer_)) return std::nullopt;
  if (picker_->GetActor() != surface_actor_.Get()) return std::nullopt;
  double p[3], n[3];
  picker_->GetPickPosition(p);
  picker_->GetPickNormal(n);
  SurfacePick pick{Eigen::Vector3d(p[0], p[1], p[2]), Eigen::Vector3d(n[0], n[1], n[2])};
  if (pick.normal.norm() < 1e-9) pick.normal = Eigen::Vector3d::UnitZ();
  pick.normal.normalize();
  return pick;
}

void VtkView::forward_mouse(QMouseEvent* e, unsigned long vtk_event) {
  const qreal r = devicePixelRatioF();
  interactor_->SetEventInformationFlipY(int(e->position().x() * r), int(e->position().y() * r),
                                        (e->modifiers() & Qt::ControlModifier) ? 1 : 0,
                                        (e->modifiers() & Qt::ShiftModifier) ? 1 : 0);
  interactor_->InvokeEvent(vtk_event, e);
  request_render();
}

void VtkView::palpate_at(const QPoint& pos) {
  const auto pick = pick_surface(pos);
  if (!pick) {
    emit palpateTarget(Eigen::Vector3d::Zero(), false);
    return;
  }
  // The fingertip touches the skin at the cursor, pressed in by press_ along -n.
  const double radius = 0.008;
  emit palpateTarget(pick->point + pick->normal * (radius - press_), true);
}

void VtkView::mousePressEvent(QMouseEvent* e) {
  last_pos_ = e->position().toPoint();
  if ((tool_ == Tool::Paint || tool_ == Tool::Erase) && e->button() == Qt::LeftButton) {
    stroke_ = true;
    emit brushStrokeStarted();
    if (const auto pick = pick_surface(last_pos_)) emit brushDab(pick->point, pick->normal);
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
    if (const auto pick = pick_surface(pos)) emit brushDab(pick->point, pick->normal);
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
  request_render();
}

void VtkView::leaveEvent(QEvent*) {
  if (tool_ == Tool::Palpate) emit palpateTarget(Eigen::Vector3d::Zero(), false);
}

}  // namespace palpation::ui
