// The workstation window (ui/main_window.h) with its real threads and the simulated
// HandHIRO: panels present; adding and painting a tumour changes the stiffness of the
// right elements in the running simulation and undo restores them; the force plots
// receive data; trainee mode hides tumours and locks the instructor panels; the 3-D view
// shows the breast in mono and anaglyph, is presented by a native child window (no
// QOpenGLWidget: docs/gui.md) that follows the layout, takes the mouse for palpation and the
// brush, and is composited into window grabs (screenshots); in Japanese every menu, panel title and button
// the user sees is translated.
// Runs under Xvfb (the view needs an OpenGL context). No timing assertions.
#include <QtTest>

#include <functional>

#include <QAbstractButton>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QListWidget>
#include <QMenu>
#include <QMenuBar>
#include <QOpenGLWidget>
#include <QWindow>
#include <QSettings>
#include <QStandardPaths>
#include <QUndoStack>

#include "force_plots.h"
#include "main_window.h"
#include "panels.h"
#include "tumour_editor.h"
#include "vtk_view.h"

using namespace palpation;

namespace {

struct ImageStats {
  double mean_r = 0, mean_g = 0, mean_b = 0;
  double skin_fraction = 0;  // pixels with the skin's warm colour (r > g > b, r high)
  double red_cyan = 0;       // pixels where r and g/b differ strongly (anaglyph fringes)
  double bright = 0;         // pixels brighter than the background and the chest can be (lit skin)
  double blue = 0;           // saturated blue pixels (a colour map's low end; not the background)
  double tumour = 0;         // red well above green (the red tumour through the skin; not bare skin)
};

ImageStats stats(const QImage& img0) {
  const QImage img = img0.convertToFormat(QImage::Format_RGB32);
  ImageStats s;
  const int n = img.width() * img.height();
  for (int y = 0; y < img.height(); ++y) {
    const QRgb* row = reinterpret_cast<const QRgb*>(img.constScanLine(y));
    for (int x = 0; x < img.width(); ++x) {
      const int r = qRed(row[x]), g = qGreen(row[x]), b = qBlue(row[x]);
      s.mean_r += r;
      s.mean_g += g;
      s.mean_b += b;
      if (r > 120 && r > g + 15 && g > b) s.skin_fraction += 1;
      if (std::abs(r - (g + b) / 2) > 60) s.red_cyan += 1;
      if (r + g + b > 3 * 150) s.bright += 1;
      if (b > 120 && b > r + 60 && b > g + 30) s.blue += 1;
      if (r > 120 && r > g + 70) s.tumour += 1;
    }
  }
  s.mean_r /= n;
  s.mean_g /= n;
  s.mean_b /= n;
  s.skin_fraction /= n;
  s.red_cyan /= n;
  s.bright /= n;
  s.blue /= n;
  s.tumour /= n;
  return s;
}

}  // namespace

class TstUiMainWindow : public QObject {
  Q_OBJECT

 private:
  std::unique_ptr<ui::MainWindow> w_;

  void pump() { QTest::qWait(20); }
  // Waits until the simulation has applied every command posted so far.
  bool synced() {
    const auto want = w_->workstation().commands_posted();
    QDeadlineTimer deadline(10000);
    while (w_->workstation().commands_applied() < want && !deadline.hasExpired()) QTest::qWait(10);
    return w_->workstation().commands_applied() >= want;
  }
  // The window retranslates its own strings at once; the panels follow on the LanguageChange
  // event that installing the translator posts to the window: delivered here.
  bool set_language(const QString& code) {
    const bool ok = w_->set_language(code);
    QCoreApplication::sendPostedEvents(nullptr, QEvent::LanguageChange);
    return ok;
  }
  // What the user reads in the menus (titles and actions, recursively), on the dock
  // titles and on the panels' buttons, in a fixed order. The Language menu is left out: it
  // names each language in itself.
  QStringList visible_strings() const {
    QStringList out;
    std::function<void(const QList<QAction*>&)> walk = [&](const QList<QAction*>& actions) {
      for (QAction* a : actions) {
        if (a->isSeparator()) continue;
        if (QMenu* m = a->menu()) {
          if (m->title().startsWith(QLatin1String("Language"))) continue;
          out << m->title();
          walk(m->actions());
        } else if (!a->text().isEmpty()) {
          out << a->text();
        }
      }
    };
    walk(w_->menuBar()->actions());
    for (auto* d : w_->findChildren<QDockWidget*>()) {
      out << d->windowTitle();
      for (auto* b : d->findChildren<QAbstractButton*>())
        if (!b->text().isEmpty()) out << b->text();
    }
    return out;
  }

 private slots:
  void initTestCase() {
    QStandardPaths::setTestModeEnabled(true);
    QSettings().remove(QStringLiteral("language"));  // a failed run leaves Japanese stored
    ui::VtkView::use_default_surface_format();
    app::live::WorkstationOptions opt;
    opt.scenario = app::live::default_workstation_scenario();
    opt.haptic_priority = 0;
    w_ = std::make_unique<ui::MainWindow>(std::make_unique<app::live::Workstation>(opt));
    w_->resize(1200, 800);
    w_->show();
    QVERIFY(QTest::qWaitForWindowExposed(w_.get()));
    QTRY_VERIFY_WITH_TIMEOUT(w_->patient_ready(), 120000);
  }

  void window_has_panels() {
    QCOMPARE(w_->instructor_docks().size(), 4);
    QVERIFY(w_->forces_dock() != nullptr);
    QStringList titles;
    for (auto* d : w_->findChildren<QDockWidget*>()) titles << d->windowTitle();
    for (const char* t : {"Patient", "Tumours", "Forces", "Simulation", "Device"}) QVERIFY2(titles.contains(QLatin1String(t)), t);
    QVERIFY(w_->menuBar()->actions().size() >= 5);
  }

  void add_tumour_and_undo() {
    auto& ws = w_->workstation();
    ui::TumourEditor* ed = w_->editor();
    const auto g = ws.geometry();
    QVERIFY(g);
    const std::vector<double> before = ed->young();
    // A 1 cm sphere of 300 kPa at x = 0.10 m, 2 cm up: outside the patient's tumour.
    const Eigen::Vector3d c(0.10, 0.02, 0.02);
    const int n = ed->add_shape(app::live::TumourShape::Sphere, c, Eigen::Vector3d::Constant(0.01), 300000.0);
    QVERIFY(n > 0);
    QVERIFY(synced());
    const auto young = ws.applied_young();
    int inside = 0;
    for (std::size_t e = 0; e < young.size(); ++e) {
      const bool in = (g->centroid[e] - c).norm() <= 0.01;
      if (in) {
        QCOMPARE(young[e], 300000.0);
        ++inside;
      } else {
        QCOMPARE(young[e], before[e]);
      }
    }
    QCOMPARE(inside, n);
    ed->undo_stack()->undo();
    QVERIFY(synced());
    QVERIFY(ws.applied_young() == before);
    ed->undo_stack()->redo();
    QVERIFY(synced());
    QVERIFY(ws.applied_young() != before);
    ed->undo_stack()->undo();
    QVERIFY(synced());
  }

  void paint_stroke_is_one_undo_step() {
    auto& ws = w_->workstation();
    ui::TumourEditor* ed = w_->editor();
    const auto g = ws.geometry();
    const std::vector<double> before = ed->young();
    const int steps0 = ed->undo_stack()->index();
    ed->set_brush(0.01, 0.01, 200000.0);
    ed->begin_stroke(false);
    // Dabs along the skin at the top of the dome (normal +z), moving in x.
    int painted = 0;
    for (int i = 0; i < 5; ++i) painted += ed->dab(Eigen::Vector3d(0.11 + 0.005 * i, -0.02, 0.06), Eigen::Vector3d::UnitZ());
    ed->end_stroke();
    QVERIFY(painted > 0);
    QCOMPARE(ed->undo_stack()->index(), steps0 + 1);
    QCOMPARE(ed->undo_stack()->count(), steps0 + 1);
    QVERIFY(synced());
    auto young = ws.applied_young();
    int changed = 0;
    for (std::size_t e = 0; e < young.size(); ++e) {
      if (young[e] == before[e]) continue;
      ++changed;
      QCOMPARE(young[e], 200000.0);
      // Every changed element lies within the brush ball of one of the dabs.
      double best = 1e9;
      for (int i = 0; i < 5; ++i)
        best = std::min(best, (g->centroid[e] - Eigen::Vector3d(0.11 + 0.005 * i, -0.02, 0.05)).norm());
      QVERIFY(best <= 0.01 + 1e-12);
    }
    QCOMPARE(changed, painted);
    QVERIFY(w_->view()->tumour_cell_count() > 0);
    ed->undo_stack()->undo();
    QVERIFY(synced());
    QVERIFY(ws.applied_young() == before);
  }

  // An instructor working in Japanese: the undo stack and the tumour list speak Japanese,
  // while the simulation's event log (and so the recording, data that a review
  // translates) gets English; back in English the list reads English again.
  void changes_are_logged_in_english_in_japanese() {
    auto& ws = w_->workstation();
    ui::TumourEditor* ed = w_->editor();
    QVERIFY(set_language(QStringLiteral("ja")));
    const std::size_t events0 = ws.events().size();
    QVERIFY(ed->add_shape(app::live::TumourShape::Sphere, Eigen::Vector3d(0.10, 0.02, 0.02), Eigen::Vector3d::Constant(0.01),
                          300000.0) > 0);
    ed->set_brush(0.01, 0.01, 200000.0);
    ed->begin_stroke(false);
    QVERIFY(ed->dab(Eigen::Vector3d(0.12, -0.02, 0.06), Eigen::Vector3d::UnitZ()) > 0);
    ed->end_stroke();
    QVERIFY(synced());
    const QString add = ed->undo_stack()->text(ed->undo_stack()->index() - 2);
    const QString stroke = ed->undo_stack()->text(ed->undo_stack()->index() - 1);
    QVERIFY2(add.startsWith(QStringLiteral("腫瘍を追加: 球")), qPrintable(add));
    QVERIFY2(stroke.startsWith(QStringLiteral("描画ストローク")), qPrintable(stroke));
    QVERIFY2(ed->tumour_names().last().contains(QStringLiteral("描画")), qPrintable(ed->tumour_names().join(QLatin1Char('|'))));
    // The tumour list follows a language change (its names are kept in English).
    QVERIFY(set_language(QStringLiteral("en")));
    QListWidget* list = w_->tumour_panel()->list;
    QVERIFY2(list->item(list->count() - 1)->text().startsWith(QLatin1String("Painted tumour ")),
             qPrintable(list->item(list->count() - 1)->text()));
    QVERIFY2(list->item(list->count() - 2)->text().startsWith(QLatin1String("Sphere at (10.0, 2.0, 2.0) cm, 300 kPa")),
             qPrintable(list->item(list->count() - 2)->text()));
    ed->undo_stack()->undo();  // the stroke
    ed->undo_stack()->undo();  // the tumour
    QVERIFY(synced());
    QStringList logged;
    const auto events = ws.events();
    for (std::size_t i = events0; i < events.size(); ++i)
      if (events[i].kind == app::live::EventKind::Material) logged << QString::fromStdString(events[i].text());
    QVERIFY2(logged.size() == 5, qPrintable(logged.join(QStringLiteral(" | "))));
    QVERIFY2(logged[0].startsWith(QLatin1String("Add tumour: Sphere at (10.0, 2.0, 2.0) cm, 300 kPa")), qPrintable(logged[0]));
    QCOMPARE(logged[1], QStringLiteral("Paint"));  // the dab, applied at once
    QVERIFY2(logged[2].startsWith(QLatin1String("Paint stroke (")) && logged[2].endsWith(QLatin1String(" elements)")),
             qPrintable(logged[2]));
    QVERIFY2(logged[3].startsWith(QLatin1String("Undo: Paint stroke (")), qPrintable(logged[3]));
    QVERIFY2(logged[4].startsWith(QLatin1String("Undo: Add tumour: Sphere at")), qPrintable(logged[4]));
  }

  // The brush through the real mouse path: pick on the 3-D view, drag, release.
  void paint_with_the_mouse() {
    ui::VtkView* v = w_->view();
    ui::TumourEditor* ed = w_->editor();
    const QPoint c = v->rect().center();
    const auto pick = v->pick_surface(c);
    QVERIFY(pick);
    QVERIFY(pick->point.z() > 0.01);   // on the dome, above the chest wall
    QVERIFY(pick->normal.z() > 0.0);   // outward, toward the camera side
    QVERIFY(!v->pick_surface(QPoint(2, 2)));  // the corner: no skin there
    const int index0 = ed->undo_stack()->index();
    // The window takes the brush from the Tumours panel at the start of a stroke.
    w_->tumour_panel()->young->setValue(150.0);  // kPa: differs from tissue and the patient's tumour
    v->set_tool(ui::VtkView::Tool::Paint);
    QTest::mousePress(v, Qt::LeftButton, Qt::NoModifier, c);
    for (int i = 1; i <= 5; ++i) {
      QMouseEvent move(QEvent::MouseMove, QPointF(c + QPoint(4 * i, 0)), v->mapToGlobal(QPointF(c + QPoint(4 * i, 0))),
                       Qt::NoButton, Qt::LeftButton, Qt::NoModifier);
      QApplication::sendEvent(v, &move);
    }
    QTest::mouseRelease(v, Qt::LeftButton, Qt::NoModifier, c + QPoint(20, 0));
    v->set_tool(ui::VtkView::Tool::Camera);
    QCOMPARE(ed->undo_stack()->index(), index0 + 1);
    QVERIFY(synced());
    ed->undo_stack()->undo();
    QVERIFY(synced());
  }

  // The view presents in a native child window, not a QOpenGLWidget (with one of those
  // Qt composes the whole window with OpenGL every frame: docs/gui.md). The window fills
  // the view and follows it when the dock layout changes size.
  void view_is_a_native_window() {
    ui::VtkView* v = w_->view();
    QVERIFY2(w_->findChildren<QOpenGLWidget*>().isEmpty(), "a QOpenGLWidget makes Qt compose the whole window with OpenGL");
    QWindow* win = v->native_window();
    QVERIFY(win && win->handle());
    QTRY_VERIFY(win->isExposed());
    QCOMPARE(win->size(), v->size());
    // The Forces dock closed: the view takes its height.
    const QSize before = v->size();
    w_->forces_dock()->hide();
    QTRY_VERIFY(v->height() > before.height());
    QTRY_COMPARE(win->size(), v->size());
    QCOMPARE(win->mapToGlobal(QPoint(0, 0)), v->mapToGlobal(QPoint(0, 0)));
    QCOMPARE(v->grabFramebuffer().size(), v->size());
    w_->forces_dock()->show();
    QTRY_COMPARE(v->size(), before);
    QTRY_COMPARE(win->size(), before);
  }

  // Mouse palpation and the brush through the native window, as the user's mouse reaches
  // them (QTest's events go through the window system interface to the QWindow).
  void mouse_reaches_the_view_through_its_window() {
    ui::VtkView* v = w_->view();
    QWindow* win = v->native_window();
    const QPoint c = v->rect().center();
    // Palpate: the fingertip follows the cursor; the wheel presses in.
    v->set_tool(ui::VtkView::Tool::Palpate);
    int targets = 0;
    bool present = false;
    Eigen::Vector3d at = Eigen::Vector3d::Zero();
    const auto conn = connect(v, &ui::VtkView::palpateTarget, this, [&](const Eigen::Vector3d& p, bool on) {
      ++targets;
      at = p;
      present = on;
    });
    const auto disconnect_spy = qScopeGuard([conn] { QObject::disconnect(conn); });
    QTest::mouseMove(win, c);
    QTRY_VERIFY(targets > 0);
    QVERIFY(present);
    QVERIFY2(at.z() > 0.01, "on the dome");
    const double depth0 = v->press_depth();
    QWheelEvent wheel(QPointF(c), win->mapToGlobal(QPointF(c)), QPoint(), QPoint(0, 120), Qt::NoButton, Qt::NoModifier,
                      Qt::NoScrollPhase, false);
    QCoreApplication::sendEvent(win, &wheel);
    QVERIFY(v->press_depth() > depth0);
    // Leaving the window lifts the fingertip.
    QEvent leave(QEvent::Leave);
    QCoreApplication::sendEvent(win, &leave);
    QVERIFY(!present);
    v->set_tool(ui::VtkView::Tool::Camera);
    // The brush: press, drag, release on the window is one undo step.
    ui::TumourEditor* ed = w_->editor();
    const int index0 = ed->undo_stack()->index();
    w_->tumour_panel()->young->setValue(150.0);
    v->set_tool(ui::VtkView::Tool::Paint);
    QTest::mousePress(win, Qt::LeftButton, Qt::NoModifier, c);
    for (int i = 1; i <= 5; ++i) QTest::mouseMove(win, c + QPoint(4 * i, 0));
    QTest::mouseRelease(win, Qt::LeftButton, Qt::NoModifier, c + QPoint(20, 0));
    v->set_tool(ui::VtkView::Tool::Camera);
    QCOMPARE(ed->undo_stack()->index(), index0 + 1);
    QVERIFY(synced());
    ed->undo_stack()->undo();
    QVERIFY(synced());
    // Palpating took the device over from the scripted hand (MainWindow): give it back.
    w_->workstation().device().set_mode(app::live::HandMode::Script);
  }

  // A window grab (the trainer's --screenshot, File > Save screenshot) shows the breast
  // where the view sits: QWidget::grab leaves the native window out, the view's frame is
  // read back and painted in.
  void window_grab_shows_the_view() {
    ui::VtkView* v = w_->view();
    v->set_tumours_visible(false);
    QTest::qWait(200);
    const QRect r(v->mapTo(w_.get(), QPoint(0, 0)), v->size());
    const QImage shot = ui::VtkView::grab_with_views(w_.get());
    QCOMPARE(shot.size(), w_->size() * shot.devicePixelRatio());
    const ImageStats in_view = stats(shot.copy(r));
    const ImageStats plain = stats(w_->grab().toImage().copy(r));
    qInfo("window grab, the view's part: skin %.3f composited, %.3f in QWidget::grab alone", in_view.skin_fraction,
          plain.skin_fraction);
    QVERIFY2(in_view.skin_fraction > 0.05, "the breast in the screenshot");
    QVERIFY2(in_view.bright > 0.05, "lit skin in the screenshot");
    v->set_tumours_visible(true);
  }

  // (Not "..._data": QtTest takes a slot ending in _data for a data function and never ran it.)
  void plots_are_fed() {
    ui::ForcePlots* p = w_->plots();
    QTRY_VERIFY_WITH_TIMEOUT(p->point_count(1) > 30, 30000);
    QTRY_VERIFY_WITH_TIMEOUT(p->shown_points() > 30, 30000);
    const QString csv = QDir::temp().filePath(QStringLiteral("tst_ui_forces.csv"));
    QVERIFY(p->export_csv(csv));
    QFile f(csv);
    QVERIFY(f.open(QIODevice::ReadOnly));
    QVERIFY(f.readLine().startsWith("t,finger,x,fmag,fz,sim_fmag,sim_fz"));
    // Both forces: the simulated contact force exceeds the device limit during the
    // scripted deep palpation, the force sent to the device never does.
    QTRY_VERIFY_WITH_TIMEOUT(p->max_simulated(1) > 4.0 + 0.2, 30000);
    QVERIFY(p->max_sent(1) <= 4.0 + 1e-6);
    p->set_paused(true);
    const int n = p->point_count(1);
    QTest::qWait(300);
    QCOMPARE(p->point_count(1), n);
    p->set_paused(false);
  }

  void view_shows_breast_mono_and_anaglyph() {
    ui::VtkView* v = w_->view();
    // The instructor's view: the red tumour through the translucent skin (the skin blended
    // over it in one pass: vtk_view.cpp's BlendedSkinActor).
    v->set_stereo(ui::VtkView::Stereo::Mono);
    QVERIFY(v->tumours_visible());
    const ImageStats seen = stats(v->grabFramebuffer());
    // Opaque skin without the red tumour: in mono nothing is strongly red or cyan.
    v->set_tumours_visible(false);
    v->set_stereo(ui::VtkView::Stereo::Mono);
    QTest::qWait(200);
    const ImageStats mono = stats(v->grabFramebuffer());
    qInfo("mono: mean rgb %.0f %.0f %.0f, skin %.3f; tumour-red %.4f shown, %.4f hidden", mono.mean_r, mono.mean_g,
          mono.mean_b, mono.skin_fraction, seen.tumour, mono.tumour);
    QVERIFY2(seen.tumour > mono.tumour + 0.005, "the tumour shows through the skin");  // measured 0.013 against 0.004 (the pink fingertip)
    QVERIFY2(mono.skin_fraction > 0.05, "the breast covers part of the view");
    QVERIFY2(mono.bright > 0.05, "lit skin present");
    // A wide eye separation makes the two eyes' images differ clearly at every edge.
    v->set_eye_angle(8.0);
    QVERIFY(v->set_stereo(ui::VtkView::Stereo::Anaglyph));
    QTest::qWait(200);
    const ImageStats ana = stats(v->grabFramebuffer());
    qInfo("anaglyph: mean rgb %.0f %.0f %.0f, red/cyan %.3f", ana.mean_r, ana.mean_g, ana.mean_b, ana.red_cyan);
    qInfo("bright: mono %.3f anaglyph %.3f", mono.bright, ana.bright);
    QVERIFY2(ana.bright > 0.05, "the breast is still drawn in anaglyph");
    // Not the mono image again: anaglyph desaturates and splits the eyes into channels.
    QVERIFY(std::abs(ana.mean_r - mono.mean_r) + std::abs(ana.mean_g - mono.mean_g) + std::abs(ana.mean_b - mono.mean_b) > 1.0);
    QVERIFY(ana.mean_r > 10);  // not an empty black image
    QVERIFY(v->set_stereo(ui::VtkView::Stereo::Mono));
    v->set_eye_angle(2.0);
    v->set_tumours_visible(true);
  }

  // The light rendering style (docs/gui.md): under Xvfb the renderer is Mesa's software one,
  // so the view chose the light style by itself; View > Fast rendering turns it off and on,
  // and the breast is drawn either way.
  void fast_rendering_style() {
    ui::VtkView* v = w_->view();
    QVERIFY(!v->gl_renderer().isEmpty());
    qInfo("GL_RENDERER: %s", qPrintable(v->gl_renderer()));
    QVERIFY2(v->software_renderer(), qPrintable(v->gl_renderer()));
    QVERIFY(ui::VtkView::is_software_renderer(QStringLiteral("llvmpipe (LLVM 15.0.6, 256 bits)")));
    QVERIFY(ui::VtkView::is_software_renderer(QStringLiteral("GDI Generic (Software Rasterizer)")));
    QVERIFY(!ui::VtkView::is_software_renderer(QStringLiteral("NVIDIA GeForce RTX 3060/PCIe/SSE2")));
    QVERIFY(v->light_style());
    auto* fast = w_->findChild<QAction*>(QStringLiteral("fast_rendering"));
    QVERIFY(fast && fast->isCheckable());
    QVERIFY(fast->isChecked());
    const ImageStats light = stats(v->grabFramebuffer());
    fast->trigger();  // off: the full style
    QVERIFY(!fast->isChecked());
    QVERIFY(!v->light_style());
    QCOMPARE(QSettings().value(QStringLiteral("view/fast_rendering")).toBool(), false);
    const ImageStats full = stats(v->grabFramebuffer());
    fast->trigger();  // on again
    QVERIFY(fast->isChecked());
    QVERIFY(v->light_style());
    QCOMPARE(QSettings().value(QStringLiteral("view/fast_rendering")).toBool(), true);
    const ImageStats again = stats(v->grabFramebuffer());
    qInfo("skin/bright/tumour: light %.3f %.3f %.4f, full %.3f %.3f %.4f", light.skin_fraction, light.bright, light.tumour,
          full.skin_fraction, full.bright, full.tumour);
    for (const ImageStats* s : {&light, &full, &again}) {
      QVERIFY2(s->skin_fraction > 0.05, "the breast covers part of the view");
      QVERIFY2(s->bright > 0.02, "lit skin present");  // translucent (instructor): measured 0.044 light, 0.079 full
      QVERIFY2(s->tumour > 0.003, "the tumour shows through the skin");
    }
    // Not the same picture: the background differs (plain against the gradient).
    QVERIFY(std::abs(light.mean_r - full.mean_r) + std::abs(light.mean_g - full.mean_g) + std::abs(light.mean_b - full.mean_b) > 1.0);
    QSettings().remove(QStringLiteral("view/fast_rendering"));
  }

  // Quad-buffer stereo where the display has no stereo visuals (Xvfb, offscreen): a clear
  // reason and the view falls back to anaglyph, still drawing the breast.
  void quad_buffer_falls_back_to_anaglyph() {
    ui::VtkView* v = w_->view();
    QString probe;
    if (ui::VtkView::quad_buffer_available(&probe)) QSKIP("this display grants stereo buffers: no fallback to test");
    QVERIFY(!probe.isEmpty());
    QString why;
    QVERIFY(!v->set_stereo(ui::VtkView::Stereo::QuadBuffer, &why));
    qInfo("%s", qPrintable(why));
    QVERIFY(why.contains(QLatin1String("not available")) && why.contains(QLatin1String("anaglyph")));
    QCOMPARE(v->stereo(), ui::VtkView::Stereo::Anaglyph);
    QTest::qWait(200);
    QVERIFY(stats(v->grabFramebuffer()).bright > 0.02);
    QVERIFY(v->set_stereo(ui::VtkView::Stereo::Mono));
  }

  // The stress colour map: the workstation adds nodal von Mises stress to the snapshots
  // while it is on; the pressed breast shows the map's colours (blue at rest, warmer
  // where it is stressed) instead of the skin tone, with the scalar bar.
  void stress_colour_map() {
    ui::VtkView* v = w_->view();
    v->set_tumours_visible(false);
    w_->workstation().set_stress_enabled(true);
    v->set_colour_mode(ui::VtkView::ColourMap::Stress);
    QTRY_VERIFY_WITH_TIMEOUT((w_->workstation().snapshot().von_mises.size() == w_->workstation().geometry()->rest.size()),
                             20000);
    float vmax = 0;
    QTRY_VERIFY_WITH_TIMEOUT(([&] {
                               vmax = 0;
                               for (float x : w_->workstation().snapshot().von_mises) vmax = std::max(vmax, x);
                               return vmax > 100.0f;  // Pa: the scripted finger presses
                             }()),
                             30000);
    QTest::qWait(200);
    const ImageStats st = stats(v->grabFramebuffer());
    qInfo("stress map: max %.0f Pa; skin %.3f, blue %.3f", double(vmax), st.skin_fraction, st.blue);
    QVERIFY2(st.skin_fraction < 0.02, "the colour map replaces the skin tone");
    QVERIFY2(st.blue > 0.05, "mostly low stress: the map's blue");
    w_->workstation().set_stress_enabled(false);
    v->set_colour_mode(ui::VtkView::ColourMap::None);
    QTRY_VERIFY_WITH_TIMEOUT(w_->workstation().snapshot().von_mises.empty(), 20000);
    QTest::qWait(200);
    QVERIFY(stats(v->grabFramebuffer()).skin_fraction > 0.05);
    v->set_tumours_visible(true);
  }

  void trainee_mode() {
    w_->set_trainee(true);
    QVERIFY(!w_->view()->tumours_visible());
    for (auto* d : w_->instructor_docks()) QVERIFY(!d->widget()->isEnabled());
    QVERIFY(w_->workstation().device().mode() == app::live::HandMode::Mouse);
    QCOMPARE(w_->view()->tool(), ui::VtkView::Tool::Palpate);
    w_->set_trainee(false);
    QVERIFY(w_->view()->tumours_visible());
    for (auto* d : w_->instructor_docks()) QVERIFY(d->widget()->isEnabled());
  }

  // The Japanese catalogue (translations/palpation_ja.ts, compiled into :/i18n/palpation_ja.qm
  // at build time) is there and current: the window title, the File menu, and every menu,
  // action, panel title and panel button the user sees differ between Japanese and English
  // (the Language menu, bilingual on purpose, aside). A missing .qm fails set_language; one
  // left stale (a string added to the code, not translated) reads the same in both.
  void language_switch() {
    QCOMPARE(w_->windowTitle(), QStringLiteral("Palpation Trainer"));
    QCOMPARE(w_->menuBar()->actions().front()->menu()->title(), QStringLiteral("&File"));
    QVERIFY(set_language(QStringLiteral("ja")));
    QCOMPARE(w_->windowTitle(), QStringLiteral("触診トレーナー"));
    QCOMPARE(w_->menuBar()->actions().front()->menu()->title(), QStringLiteral("ファイル(&F)"));
    const QStringList ja = visible_strings();
    const QString all = ja.join(QStringLiteral(" | "));
    QVERIFY2(ja.contains(QStringLiteral("腫瘍")), qPrintable(all));                  // a panel title
    QVERIFY2(ja.contains(QStringLiteral("記録を開く(&O)...")), qPrintable(all));     // File > Open recording
    QVERIFY2(ja.contains(QStringLiteral("しこりをマーク (M)")), qPrintable(all));    // the trainee's mark
    QVERIFY2(ja.contains(QStringLiteral("スキャンを取り込む...")), qPrintable(all));  // Patient panel
    // Labels the panels fill: the chosen phantom's description (set when it was chosen, in
    // English) and the simulation's state (app::live::LiveStats, English).
    QCOMPARE(w_->patient_panel()->chosen(), QStringLiteral("phantom:breast"));
    QCOMPARE(w_->patient_panel()->description->text(), QStringLiteral("論文の乳房と腫瘍（x = 12.5 cm、107 kPa）。"));
    auto* sim_panel = w_->findChild<ui::SimulationPanel*>();
    QVERIFY(sim_panel);
    QTRY_VERIFY2(sim_panel->state->text().startsWith(QStringLiteral("実行中")), qPrintable(sim_panel->state->text()));
    // Back to English. Compared after the switch: retranslate() names the undo actions
    // "Undo" and "Redo", without the command that the undo stack appended before.
    QVERIFY(set_language(QStringLiteral("en")));
    QCOMPARE(w_->windowTitle(), QStringLiteral("Palpation Trainer"));
    QTRY_VERIFY2(sim_panel->state->text().startsWith(QStringLiteral("running")), qPrintable(sim_panel->state->text()));
    const QStringList en = visible_strings();
    QVERIFY2(en.size() > 40 && en.contains(QStringLiteral("&Open recording...")), qPrintable(en.join(QStringLiteral(" | "))));
    QCOMPARE(ja.size(), en.size());
    QStringList untranslated;
    for (qsizetype i = 0; i < en.size(); ++i)
      if (ja[i] == en[i]) untranslated << en[i];
    QVERIFY2(untranslated.isEmpty(), qPrintable(QStringLiteral("still English in Japanese: ") + untranslated.join(QStringLiteral(" | "))));
  }

  void cleanupTestCase() { w_.reset(); }
};

QTEST_MAIN(TstUiMainWindow)
#include "tst_ui_main_window.moc"
