// The 3-D view: VTK 9.1 rendering inside a Qt 6 QOpenGLWidget (Debian's VTK Qt module is
// Qt5-only; ../shared/stack-notes.md says how this is wired). Shows the deformed breast
// surface from the simulation's snapshots, the static chest, five fingertip spheres, the
// stiff (tumour) elements translucent for instructors, an optional displacement colour
// map; stereo (anaglyph, side-by-side, interlaced) and a mirrored mode for the paper's
// half-mirror display. Holds no state beyond what it displays.
#pragma once

#include <memory>
#include <vector>

#include <QOpenGLWidget>
#include <QString>

#include <Eigen/Core>
#include <vtkNew.h>
#include <vtkSmartPointer.h>

#include "workstation.h"

class vtkActor;
class vtkCellPicker;
class vtkGenericOpenGLRenderWindow;
class vtkGenericRenderWindowInteractor;
class vtkPoints;
class vtkPolyData;
class vtkPolyDataNormals;
class vtkRenderer;
class vtkSphereSource;
class vtkTextActor;
class vtkUnstructuredGrid;
class vtkFloatArray;

namespace palpation::ui {

class VtkView : public QOpenGLWidget {
  Q_OBJECT

 public:
  enum class Stereo { Mono, Anaglyph, SideBySide, Interlaced, QuadBuffer };
  enum class Tool { Camera, Paint, Erase, Palpate };
  enum class CameraPreset { Oblique, Top, Side, Front };

  explicit VtkView(QWidget* parent = nullptr);
  ~VtkView() override;

  /// A new patient: rebuilds the surface and tumour geometry.
  void set_patient(std::shared_ptr<const app::PatientGeometry> g);
  /// The newest snapshot (deformed nodes, fingertips). Schedules a render.
  void show_snapshot(const app::RenderSnapshot& s);
  /// Elements whose modulus is above the tissue's are drawn as tumours.
  void set_element_young(const std::vector<double>& young);
  void set_tumours_visible(bool on);
  bool tumours_visible() const { return tumours_visible_; }
  int tumour_cell_count() const;
  void set_colour_map(bool on);
  /// False (and `why` set) when the mode is not available here (quad-buffer without
  /// stereo buffers); the view then stays in its previous mode.
  bool set_stereo(Stereo mode, QString* why = nullptr);
  Stereo stereo() const { return stereo_; }
  void set_eye_angle(double degrees);
  void set_mirrored(bool on);
  void set_camera(CameraPreset p);
  void set_tool(Tool t) { tool_ = t; }
  Tool tool() const { return tool_; }
  void set_overlay_text(const QString& text);
  /// Press depth of the mouse fingertip (m, >= 0).
  double press_depth() const { return press_; }
  /// Surface point under a widget position (world, m) and the outward normal.
  bool pick_surface(const QPoint& pos, Eigen::Vector3d& point, Eigen::Vector3d& normal);
  /// Frames rendered so far (for the measured frame rate).
  quint64 frames() const { return frames_; }

 signals:
  /// A brush dab at a surface point (Paint or Erase tool); `first` starts a stroke.
  void brushDab(const Eigen::Vector3d& point, const Eigen::Vector3d& normal, bool first);
  void brushStrokeEnded();
  /// Where the mouse fingertip should be (Palpate tool); present = false lifts it away.
  void palpateTarget(const Eigen::Vector3d& centre, bool present);

 protected:
  void initializeGL() override;
  void resizeGL(int w, int h) override;
  void paintGL() override;
  void mousePressEvent(QMouseEvent* e) override;
  void mouseMoveEvent(QMouseEvent* e) override;
  void mouseReleaseEvent(QMouseEvent* e) override;
  void wheelEvent(QWheelEvent* e) override;
  void leaveEvent(QEvent* e) override;

 private:
  void palpate_at(const QPoint& pos);
  void forward_mouse(QMouseEvent* e, unsigned long vtk_event);

  vtkNew<vtkGenericOpenGLRenderWindow> window_;
  vtkNew<vtkGenericRenderWindowInteractor> interactor_;
  vtkNew<vtkRenderer> renderer_;
  vtkNew<vtkPoints> points_;
  vtkNew<vtkPolyData> surface_;
  vtkNew<vtkPolyDataNormals> normals_;
  vtkNew<vtkActor> surface_actor_;
  vtkNew<vtkFloatArray> displacement_;
  vtkNew<vtkUnstructuredGrid> tumour_grid_;
  vtkNew<vtkActor> tumour_actor_;
  vtkNew<vtkActor> chest_actor_;
  std::vector<vtkSmartPointer<vtkActor>> finger_actors_;
  vtkNew<vtkCellPicker> picker_;
  vtkNew<vtkTextActor> overlay_;
  std::shared_ptr<const app::PatientGeometry> geometry_;
  std::vector<double> young_;
  Stereo stereo_ = Stereo::Mono;
  Tool tool_ = Tool::Camera;
  bool tumours_visible_ = true, colour_map_ = false, mirrored_ = false, stroke_ = false, pressing_ = false;
  bool initialized_ = false;
  double press_ = 0.0;
  QPoint last_pos_;
  quint64 frames_ = 0;
};

}  // namespace palpation::ui
