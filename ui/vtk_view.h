// The 3-D view: VTK 9.1 rendering into a native child window (a QWindow with its own
// QOpenGLContext, in QWidget::createWindowContainer) inside a plain QWidget (Debian's VTK Qt
// module is Qt5-only; ../shared/stack-notes.md says how VTK is wired to a Qt context). Not a
// QOpenGLWidget: with one of those in a window, Qt 6 composes the whole top-level window with
// OpenGL on every update, which under software GL cost 50-76 ms a frame (docs/gui.md); the
// native window presents only the view's own pixels and the rest of the window stays raster.
// A native window is not in QWidget::grab(): grabFramebuffer() reads VTK's frame back and
// grab_with_views() composites it into a window grab (screenshots, exported frames). Shows the deformed breast
// surface from the simulation's snapshots, the static chest, five fingertip spheres, the
// stiff (tumour) elements and the boundary of the glandular layer through a translucent
// skin for instructors, an optional colour
// map (displacement, or von Mises stress computed by the simulation thread) with a scalar
// bar; stereo (anaglyph, side-by-side, interlaced, quad-buffer where the display grants
// stereo buffers) and a mirrored mode for the paper's half-mirror display. Holds no state
// beyond what it displays.
//
// Cost per frame (docs/gui.md, measured under Xvfb with llvmpipe): a snapshot only
// rewrites the points array, the point normals (area-weighted, over the surface
// triangles) and the scalars in place and marks them Modified(); nothing is re-created
// and no VTK filter runs per frame; the tumour's boundary faces (from the tumour document,
// app/live/tumour_document.h) are taken when the materials change, not per frame. A snapshot that moves nothing renders nothing. Under
// software OpenGL (llvmpipe and the like) the view draws in a light style by itself
// (set_render_style; View > Fast rendering): a plain background, no specular on the skin,
// an unlit chest, which the renderer shades per pixel at a cost and which inform nobody.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <vector>

#include <QImage>
#include <QWidget>
#include <QString>

#include <Eigen/Core>
#include <vtkNew.h>
#include <vtkSmartPointer.h>

#include "live/workstation.h"

class QOpenGLContext;
class QOpenGLWindow;
class QWindow;
class vtkActor;
class vtkLookupTable;
class vtkScalarBarActor;
class vtkCellPicker;
class vtkGenericOpenGLRenderWindow;
class vtkGenericRenderWindowInteractor;
class vtkPoints;
class vtkPolyData;
class vtkRenderer;
class vtkSphereSource;
class vtkTextActor;
class vtkFloatArray;

namespace palpation::ui {

class ViewWindow;

class VtkView : public QWidget {
  Q_OBJECT

 public:
  enum class Stereo { Mono, Anaglyph, SideBySide, Interlaced, QuadBuffer };
  enum class Tool { Camera, Paint, Erase, Palpate };
  enum class CameraPreset { Oblique, Top, Side, Front };

  explicit VtkView(QWidget* parent = nullptr);
  ~VtkView() override;

  /// A new patient: rebuilds the surface; no tumours until show_tumours.
  void set_patient(std::shared_ptr<const app::live::PatientGeometry> g);
  /// The newest snapshot (deformed nodes, fingertips). Schedules a render.
  void show_snapshot(const app::live::RenderSnapshot& s);
  /// Draws the document's tumours (its tumour elements' boundary faces) on the patient
  /// shown (the document's patient must be it).
  void show_tumours(const app::live::TumourDocument& doc);
  void set_tumours_visible(bool on);
  bool tumours_visible() const { return tumours_visible_; }
  /// The coverage overlay (docs/training.md): the skin's faces coloured by the highest
  /// pressure level reached, `levels` one per PatientGeometry::surface face (0 none,
  /// 1 light, 2 medium, 3 deep: LiveExam::surface_levels), in the colours of the exam
  /// report's coverage map (kCoverageColour). Drawn over the skin while visible; the
  /// caller decides whether the mode allows it.
  void set_coverage(const std::vector<unsigned char>& levels);
  void set_coverage_visible(bool on);
  bool coverage_visible() const { return coverage_visible_; }
  /// Faces the overlay shows at each level (none, light, medium, deep), for tests.
  std::array<int, 4> coverage_counts() const { return coverage_counts_; }
  /// Grey none, yellow light, orange medium, red deep (RGB 0-255), as in coverage.png.
  static constexpr unsigned char kCoverageColour[4][3] = {{215, 215, 215}, {250, 220, 90}, {245, 150, 50}, {200, 40, 40}};
  int tumour_cell_count() const;
  /// Faces of the deeper tissue layer's boundary drawn (live::deep_layer_faces),
  /// for tests; shown with the tumours, through the translucent skin.
  int layer_face_count() const { return layer_faces_; }
  enum class ColourMap { None, Displacement, Stress };
  /// Displacement (mm, 0-15) or von Mises stress (kPa, from the snapshot's von_mises;
  /// the workstation computes it while the stress map is on), with a scalar bar.
  void set_colour_mode(ColourMap m);
  ColourMap colour_mode() const { return colour_map_; }
  /// The displacement map on or off (the View menu's action).
  void set_colour_map(bool displacement) { set_colour_mode(displacement ? ColourMap::Displacement : ColourMap::None); }
  void set_stress_map(bool on) { set_colour_mode(on ? ColourMap::Stress : ColourMap::None); }
  /// False (and `why` set) when the mode is not available here. Quad-buffer asks the
  /// display for a stereo OpenGL format; where it is refused (Xvfb, most desktop GPUs)
  /// the view falls back to anaglyph and `why` says so.
  bool set_stereo(Stereo mode, QString* why = nullptr);
  /// Whether this display grants an OpenGL context with stereo (quad) buffers; `why`
  /// gets the reason when not. Probes once with a small native window.
  static bool quad_buffer_available(QString* why = nullptr);
  /// The default OpenGL format the view needs: a 3.2 core context with depth and stencil
  /// (interlaced stereo uses the stencil), no vsync. Set it (QSurfaceFormat::
  /// setDefaultFormat) before the QApplication's first window: the trainer's main() and
  /// the GUI tests do.
  static void use_default_surface_format();
  Stereo stereo() const { return stereo_; }
  /// The rendering style (docs/gui.md): Full (gradient background, specular skin, lit
  /// chest) or Light, for software OpenGL: a plain background, no specular on the skin, an
  /// unlit chest; the breast, the fingertips, the tumours and the colour maps as in Full.
  /// Auto (the default) is Light where the context's GL_RENDERER is a software one
  /// (is_software_renderer), read once when the context exists; Full until then.
  enum class RenderStyle { Auto, Full, Light };
  void set_render_style(RenderStyle s);
  RenderStyle render_style() const { return style_; }
  /// Whether the light style is in effect now.
  bool light_style() const { return light_; }
  /// GL_RENDERER of the view's context; empty before the context exists.
  QString gl_renderer() const { return gl_renderer_; }
  bool software_renderer() const { return software_; }
  /// llvmpipe, softpipe, swrast, "Software" (Microsoft's GDI renderer and others).
  static bool is_software_renderer(const QString& gl_renderer);
  void set_eye_angle(double degrees);
  void set_mirrored(bool on);
  void set_camera(CameraPreset p);
  void set_tool(Tool t) { tool_ = t; }
  Tool tool() const { return tool_; }
  void set_overlay_text(const QString& text);
  /// Press depth of the mouse fingertip (m, >= 0).
  double press_depth() const { return press_; }
  /// A point of the skin (world, m) and its outward unit normal.
  struct SurfacePick {
    Eigen::Vector3d point, normal;
  };
  /// The skin under a widget position; nothing when the position misses it.
  std::optional<SurfacePick> pick_surface(const QPoint& pos);
  /// Frames rendered so far (for the measured frame rate).
  quint64 frames() const { return frames_; }
  /// Schedules a new frame (the native window's next update request). Not QWidget::update:
  /// the widget under the window paints nothing.
  void request_render();
  /// Renders the current scene and presents it now (VTK render, blit, swap of the view's
  /// window), when the window is on screen; false otherwise. The view-alone benchmark.
  bool render_now();
  /// Benchmark (docs/gui.md): renders the current scene `n` times in VTK alone (no blit,
  /// no presentation), waiting for each; ms per frame.
  double bench_render(int n);
  /// The view's image as VTK draws it now (rendered afresh and read back from VTK's
  /// framebuffer; mirrored as shown; the left eye in quad-buffer stereo). Null before the
  /// view's window exists.
  QImage grabFramebuffer();
  /// `w->grab()` with the frame of every visible 3-D view in w's window painted where the
  /// view sits (QWidget::grab leaves a native child window out). For screenshots.
  static QImage grab_with_views(QWidget* w);
  /// The native window the view presents in (tests send it mouse events).
  QWindow* native_window() const;
  /// Snapshots that changed nothing visible and so rendered nothing.
  quint64 skipped_snapshots() const { return skipped_; }
  /// Mean time of one frame (VTK render + blit + swap), ms, over the frames so far; and the
  /// time spent turning snapshots into VTK arrays (show_snapshot), ms per snapshot.
  double paint_ms() const { return frames_ ? paint_ns_ * 1e-6 / double(frames_) : 0.0; }
  /// Of paint_ms(): VTK's render (until its frame is in its own framebuffer) and the swap
  /// (the window system taking the view's pixels); the rest is the blit.
  double render_ms() const { return frames_ ? render_ns_ * 1e-6 / double(frames_) : 0.0; }
  double swap_ms() const { return frames_ ? swap_ns_ * 1e-6 / double(frames_) : 0.0; }
  double update_ms() const { return snapshots_ ? update_ns_ * 1e-6 / double(snapshots_) : 0.0; }

 signals:
  /// A brush stroke starts (Paint or Erase tool, left button pressed), dabs at the skin
  /// points it passes over, and ends (released).
  void brushStrokeStarted();
  void brushDab(const Eigen::Vector3d& point, const Eigen::Vector3d& normal);
  void brushStrokeEnded();
  /// Where the mouse fingertip should be (Palpate tool); present = false lifts it away.
  void palpateTarget(const Eigen::Vector3d& centre, bool present);
  /// The style in effect changed (set_render_style, or Auto resolved once the renderer is known).
  void lightStyleChanged(bool light);

 protected:
  void resizeEvent(QResizeEvent* e) override;
  bool event(QEvent* e) override;
  void mousePressEvent(QMouseEvent* e) override;
  void mouseMoveEvent(QMouseEvent* e) override;
  void mouseReleaseEvent(QMouseEvent* e) override;
  void wheelEvent(QWheelEvent* e) override;
  void leaveEvent(QEvent* e) override;

 private:
  void palpate_at(const QPoint& pos);
  void forward_mouse(QMouseEvent* e, unsigned long vtk_event);
  void update_normals();
  void update_scalars(const app::live::RenderSnapshot* s);
  void render_vtk();
  void apply_style();
  // The native window's side: first exposure creates the context and initializes VTK's
  // OpenGL; present() renders (when needed) and shows the frame.
  bool ensure_gl();
  bool make_current();
  void done_current();
  void present();
  friend class QuadBufferWindow;
  friend class ViewWindow;

  vtkNew<vtkGenericOpenGLRenderWindow> window_;
  vtkNew<vtkGenericRenderWindowInteractor> interactor_;
  vtkNew<vtkRenderer> renderer_;
  vtkNew<vtkPoints> points_;
  vtkNew<vtkPolyData> surface_;
  vtkNew<vtkFloatArray> normals_;        // (nnode x 3) point normals of the surface
  vtkSmartPointer<vtkActor> surface_actor_;  // a BlendedSkinActor (vtk_view.cpp)
  vtkNew<vtkFloatArray> scalars_;        // (nnode) displacement mm or stress kPa
  vtkNew<vtkLookupTable> lut_;
  vtkNew<vtkScalarBarActor> scalar_bar_;
  vtkNew<vtkPolyData> tumour_poly_;      // boundary faces of the stiff elements
  vtkNew<vtkActor> tumour_actor_;
  vtkNew<vtkPolyData> layer_poly_;       // boundary of the deeper tissue layer (glandular)
  vtkSmartPointer<vtkActor> layer_actor_;  // blended in the opaque pass, before the skin (as it is)
  vtkNew<vtkActor> chest_actor_;
  vtkNew<vtkPolyData> coverage_poly_;    // the surface triangles again, coloured per face
  vtkNew<vtkActor> coverage_actor_;
  bool coverage_visible_ = false;
  std::vector<unsigned char> shown_levels_;
  std::array<int, 4> coverage_counts_{};
  std::vector<vtkSmartPointer<vtkActor>> finger_actors_;
  vtkNew<vtkCellPicker> picker_;
  vtkNew<vtkTextActor> overlay_;
  std::shared_ptr<const app::live::PatientGeometry> geometry_;
  std::vector<float> shown_positions_, shown_stress_;  // what the last render showed
  std::array<Eigen::Vector3d, 5> shown_fingers_{};
  std::array<bool, 5> shown_active_{};
  ViewWindow* gl_window_ = nullptr;       // the native child window VTK presents in
  QWidget* container_ = nullptr;          // its container widget, filling this one
  QOpenGLContext* context_ = nullptr;     // VTK's context (owned by this widget)
  QOpenGLWindow* quad_window_ = nullptr;  // quad-buffer stereo: presents the two eyes
  QWidget* quad_container_ = nullptr;
  Stereo stereo_ = Stereo::Mono;
  Tool tool_ = Tool::Camera;
  ColourMap colour_map_ = ColourMap::None;
  RenderStyle style_ = RenderStyle::Auto;
  bool light_ = false, software_ = false;
  QString gl_renderer_;
  bool tumours_visible_ = true, mirrored_ = false, stroke_ = false, pressing_ = false;
  bool initialized_ = false, painting_ = false, pending_ = false;
  double press_ = 0.0;
  QPoint last_pos_;
  quint64 frames_ = 0, snapshots_ = 0, skipped_ = 0;
  int tumour_cells_ = 0;
  int layer_faces_ = 0;
  double paint_ns_ = 0, update_ns_ = 0, render_ns_ = 0, swap_ns_ = 0;
};

}  // namespace palpation::ui
