// In the workstation GUI: every session records, the trainee marks lumps, students
// review recordings, the patient chooser reads the library. The real window, threads and
// simulated HandHIRO (mouse palpation driven by the test), under Xvfb:
//   - a scripted session (a fingertip pressing and sliding over the breast, a tumour added
//     by the instructor, a trainee mark, a solver change) is recorded with its steps, ticks,
//     parameter changes as data and the mark;
//   - its review re-simulates it to the recorded forces (same backend, settings and thread
//     count: the same floating-point operations; asserted to 1e-9 N, the measured
//     difference is printed), play / scrub / speed move the displayed time, the view's
//     frame and the plots' cursor; markers are on the timeline; CSV and PNG frames export;
//     in Japanese its buttons and title are translated;
//   - the review scores the exam as `palpation score` does (the same hits and coverage),
//     its coverage overlay colours the pressed skin faces, Save report writes score.json
//     and report.html; a recording cut short is not scored and the review says why;
//   - a corrupted recording gives an error naming the file, the chunk and the reason, and
//     leaves the recording and the patient library byte for byte as they were;
//   - the chooser lists the built-in patients, and choosing one reaches the simulation.
#include <QtTest>

#include <QSettings>

#include <algorithm>

#include <QComboBox>
#include <QCryptographicHash>
#include <QLabel>
#include <QLineEdit>
#include <QProgressBar>
#include <QListWidget>
#include <QPushButton>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QTranslator>

#include "import_dialog.h"
#include "main_window.h"
#include "panels.h"
#include "store/patient_library.h"
#include "store/recording.h"
#include "review_window.h"
#include "score_dialog.h"
#include "tumour_editor.h"
#include "vtk_view.h"
#include "review/workstation_recorder.h"
#include "train/score_recording.h"

using namespace palpation;

namespace {
QByteArray file_hash(const QString& path) {
  QFile f(path);
  if (!f.open(QIODevice::ReadOnly)) return {};
  return QCryptographicHash::hash(f.readAll(), QCryptographicHash::Sha256);
}
}  // namespace

class TstReview : public QObject {
  Q_OBJECT

 private:
  QTemporaryDir dir_;
  QString rec_path_;

  std::unique_ptr<ui::MainWindow> make_window(const QString& record) {
    app::live::WorkstationOptions opt;
    opt.scenario = app::live::default_workstation_scenario();
    opt.haptic_priority = 0;
    auto w = std::make_unique<ui::MainWindow>(std::make_unique<app::live::Workstation>(opt), nullptr, record);
    w->resize(1200, 800);
    w->show();
    return w;
  }

 private slots:
  void initTestCase() {
    QVERIFY(dir_.isValid());
    QStandardPaths::setTestModeEnabled(true);
    qputenv("PALPATION_DB", dir_.filePath(QStringLiteral("patients.sqlite")).toUtf8());
    qputenv("PALPATION_RECORDINGS", dir_.filePath(QStringLiteral("recordings")).toUtf8());
    ui::VtkView::use_default_surface_format();
    // A run stopped half-way leaves its settings (test mode's own folder): start as a new
    // user would, in English with the default patient.
    QSettings().remove(QStringLiteral("language"));
    QSettings().remove(QStringLiteral("patient"));
    rec_path_ = dir_.filePath(QStringLiteral("scripted.palrec"));
  }

  void record_scripted_session() {
    auto w = make_window(rec_path_);
    QVERIFY(QTest::qWaitForWindowExposed(w.get()));
    QTRY_VERIFY_WITH_TIMEOUT(w->patient_ready(), 120000);
    QVERIFY(w->recorder());
    auto& ws = w->workstation();
    const auto g = ws.geometry();
    // The top of the breast; the fingertip (8 mm sphere) pressed 6 mm in and slid 2 cm along x.
    Eigen::Vector3d top = g->rest.front();
    for (const auto& p : g->rest)
      if (p.z() > top.z()) top = p;
    ws.device().set_mode(app::live::HandMode::Mouse);
    const double r = 0.008;
    QElapsedTimer clock;
    clock.start();
    bool added = false, painted = false, marked = false, params = false;
    // 2.5 s of wall time, and on until every scripted change was made (a loaded machine can
    // stall the loop in a change past the time of the next ones).
    while (clock.elapsed() < 2500 || !params) {
      const double s = std::min(1.0, double(clock.elapsed()) / 2500.0);
      const double depth = std::min(1.0, 3 * s) * 0.006;
      ws.set_mouse_finger(top + Eigen::Vector3d(0.02 * s - 0.01, 0, r - depth), true);
      if (!added && s > 0.3) {  // the instructor adds a tumour under the finger's path
        added = w->editor()->add_shape(app::live::TumourShape::Sphere, top + Eigen::Vector3d(0.005, 0, -0.02),
                                       Eigen::Vector3d::Constant(0.01), 200000.0) > 0;
        QVERIFY(added);
      }
      if (!painted && s > 0.45) {  // and paints a little stiffness with the brush (dabs, then the stroke)
        w->editor()->set_brush(0.008, 0.01, 150000.0);
        w->editor()->begin_stroke(false);
        painted = w->editor()->dab(top + Eigen::Vector3d(-0.01, 0.01, 0), Eigen::Vector3d::UnitZ()) > 0;
        w->editor()->end_stroke();
        QVERIFY(painted);
      }
      if (!marked && s > 0.6) {
        marked = w->mark_lump() == 1;
        QVERIFY(marked);
      }
      if (!params && s > 0.75) {
        sim::SimParams p = ws.options().scenario.params;
        p.solver.cg_tolerance = 1e-4;
        ws.set_params(p);
        params = true;
      }
      QTest::qWait(5);
    }
    // A loaded machine steps the simulation slowly (the sanitizer build with another GUI
    // suite beside it recorded 13 steps in those 2.7 s): the finger stays pressed until
    // the recording holds more than 20 steps, for at most 60 s more.
    QElapsedTimer more;
    more.start();
    while (w->recorder()->steps() <= 20 && more.elapsed() < 60000) QTest::qWait(20);
    ws.set_mouse_finger(top + Eigen::Vector3d(0, 0, 0.05), false);
    QTest::qWait(200);
    const std::uint64_t steps = w->recorder()->steps();
    QVERIFY2(steps > 20, qPrintable(QString::number(steps)));
    w.reset();  // closes the recording

    const app::store::Recording rec = app::store::read_recording(rec_path_.toStdString());
    QVERIFY(rec.complete);
    QCOMPARE(rec.version, app::store::kRecordingVersion);
    QCOMPARE(rec.fingers, 5);
    QVERIFY2(rec.ticks() > 1500, qPrintable(QString::number(rec.ticks())));  // 1 kHz over ~2.7 s (ticks are lost only to ring overflow)
    QVERIFY(rec.steps.size() >= steps);
    QCOMPARE(rec.header["session"]["kind"].get<std::string>(), std::string("workstation"));
    int marks = 0, young = 0, param = 0;
    double fmax = 0;
    for (const auto& e : rec.events) {
      if (e["kind"] == "mark") {
        ++marks;
        const Eigen::Vector3d p(e["position"][0].get<double>(), e["position"][1].get<double>(), e["position"][2].get<double>());
        QVERIFY2((p - top).norm() < 0.03, "the mark is where the fingertip was");
      }
      if (e["kind"] == "parameter" && e["command"] == "young") ++young;
      if (e["kind"] == "parameter" && e["command"] == "params") ++param;
    }
    for (const auto& f : rec.f) fmax = std::max(fmax, f.norm());
    QCOMPARE(marks, 1);
    QVERIFY2(young >= 2, qPrintable(QString::number(young)));  // the added tumour, the brush's dab(s)
    QCOMPARE(param, 1);
    QVERIFY2(fmax > 0.2, qPrintable(QStringLiteral("largest force sent %1 N").arg(fmax)));
  }

  void review_resimulates_and_plays() {
    QVERIFY(QFileInfo::exists(rec_path_));
    auto session = std::make_unique<app::review::ReviewSession>(rec_path_.toStdString());
    QVERIFY(session->has_steps());
    ui::ReviewWindow rw(std::move(session));
    rw.show();
    QVERIFY(QTest::qWaitForWindowExposed(&rw));
    auto& s = rw.session();
    QTRY_VERIFY_WITH_TIMEOUT(s.finished(), 300000);
    QVERIFY2(s.error().empty(), s.error().c_str());
    QCOMPARE(s.done(), s.total());
    const auto c = s.compare();
    qInfo("re-simulated %zu steps on %s: largest difference %.3g N (largest recorded step force %.3g N); forces sent vs "
          "re-simulated step forces: %.3g N",
          s.total(), s.backend().c_str(), c.max_diff, c.max_force, c.max_sent_diff);
    QVERIFY(c.max_force > 0.2);
    // Same backend, settings and thread count: the same operations in the same order.
    QVERIFY2(c.max_diff <= 1e-9, qPrintable(QString::number(c.max_diff)));
    // The forces sent at 1 kHz against the re-simulated step forces (each tick against the
    // step at or before it): recomputed here from the recording, whose step forces the
    // re-simulated ones equal (max_diff above, 1e-9 N: the bound below). Not zero: the
    // device got the simulated force times the patient's force scale (0.6 on this patient).
    const app::store::Recording rec = app::store::read_recording(rec_path_.toStdString());
    {
      const std::size_t nf = std::size_t(rec.fingers);
      double sent_diff = 0;
      std::size_t j = 0;
      for (std::size_t i = 0; i < rec.ticks(); ++i) {
        while (j + 1 < rec.steps.size() && rec.steps[j + 1].t <= rec.t[i]) ++j;
        if (rec.steps[j].t > rec.t[i]) continue;
        for (std::size_t k = 0; k < nf; ++k) {
          const double d = (rec.f[i * nf + k] - rec.steps[j].fingers[k].f).norm();
          if (std::isfinite(d)) sent_diff = std::max(sent_diff, d);
        }
      }
      QVERIFY2(sent_diff > 0.05, qPrintable(QString::number(sent_diff)));
      // The review keeps the re-simulated forces in float (7 significant digits) but
      // compares in double before storing: 1e-6 relative covers float's rounding.
      QVERIFY2(std::abs(c.max_sent_diff - sent_diff) <= 1e-6 * std::max(1.0, sent_diff),
               qPrintable(QString("reported %1 N, recomputed %2 N").arg(c.max_sent_diff).arg(sent_diff)));
    }
    QVERIFY(rw.difference_label()->text().contains(QLatin1String("Reproduced")));
    // In Japanese (the .qm compiled from translations/palpation_ja.ts): the review's own
    // strings follow a language change; a missing or stale catalogue leaves them English.
    {
      // The recorded events are data in the file (kind, arguments, English line); the list
      // shows them in the chosen language (ui/event_text.h).
      QStringList events_en;
      for (int i = 0; i < rw.marker_list()->count(); ++i) events_en << rw.marker_list()->item(i)->text();
      // Each change and mark once, though the file holds it as data and as a log line
      // (this script made every change once).
      QStringList texts;
      for (const QString& e : events_en) texts << e.section(QStringLiteral("  "), 1);
      QStringList distinct = texts;
      distinct.removeDuplicates();
      QVERIFY2(distinct.size() == texts.size(), qPrintable(QStringLiteral("listed twice: ") + texts.join(QStringLiteral(" | "))));
      QTranslator ja;
      QVERIFY(ja.load(QStringLiteral(":/i18n/palpation_ja.qm")));
      QCoreApplication::installTranslator(&ja);
      QTRY_COMPARE(rw.play_button()->text(), QStringLiteral("再生"));
      QStringList events_ja, same;
      for (int i = 0; i < rw.marker_list()->count(); ++i) events_ja << rw.marker_list()->item(i)->text();
      QCOMPARE(events_ja.size(), events_en.size());
      for (qsizetype i = 0; i < events_en.size(); ++i) {
        qInfo("event: %s | %s", qPrintable(events_en[i]), qPrintable(events_ja[i]));
        if (events_ja[i] == events_en[i]) same << events_en[i];
      }
      QVERIFY2(events_en.size() >= 3 && same.isEmpty(), qPrintable(QStringLiteral("still English: ") + same.join(QStringLiteral(" | "))));
      QVERIFY2(events_ja.join(QLatin1Char('\n')).contains(QStringLiteral("研修生のマーク 1（")), qPrintable(events_ja.join(QLatin1Char('\n'))));
      QCOMPARE(rw.windowTitle(), QStringLiteral("レビュー: scripted.palrec"));
      QStringList buttons;
      for (auto* b : rw.findChildren<QPushButton*>()) buttons << b->text();
      QVERIFY2(buttons.contains(QStringLiteral("CSV 出力...")) && buttons.contains(QStringLiteral("PNG フレーム出力...")),
               qPrintable(buttons.join(QStringLiteral(" | "))));
      QCoreApplication::removeTranslator(&ja);
      QTRY_COMPARE(rw.play_button()->text(), QStringLiteral("Play"));
      QCOMPARE(rw.marker_list()->item(0)->text(), events_en.front());
    }

    // Scrub: the time, the plots' cursor and the 3-D frame follow.
    rw.tick();
    rw.seek(0.2);
    QCOMPARE(s.time(), 0.2);
    QVERIFY(rw.time_label()->text().startsWith(QLatin1String("0:00.200")));
    QCOMPARE(rw.plot_cursor(), 0.2);
    const auto f1 = s.frame_at(0.2);
    // The finger is deepest in the tissue at the recorded step of the largest force (not at
    // a fixed share of the recording: its start holds the patient's loading, which a loaded
    // machine stretches). Sought from the second kept frame on: a loop stalled while the
    // patient loaded takes its first step with the finger already deep, so the largest
    // force can fall in the first frame, and this compares the press with that frame.
    QVERIFY2(s.frame_count() >= 2, qPrintable(QString::number(s.frame_count())));
    const double t_second = s.frame(1)->t;
    double t_press = 0;
    {
      double fbest = -1;
      for (const auto& st : rec.steps)
        for (const auto& fg : st.fingers)
          if (st.t >= t_second && fg.f.norm() > fbest) fbest = fg.f.norm(), t_press = st.t;
      QVERIFY2(fbest > 0.2 && t_press > 0.2, qPrintable(QString("%1 N at %2 s").arg(fbest).arg(t_press)));
    }
    rw.seek(t_press);
    const auto f2 = s.frame_at(t_press);
    // The body at the press against the first kept frame, before it. Not against the frame
    // at 0.2 s: a run whose press came just after 0.2 s keeps both times in one frame (they
    // are 1/30 s apart).
    QVERIFY(f1 && f2);
    const auto f0 = s.frame(0);
    QVERIFY(f0 && f0 != f2);
    // frame_at gives the newest kept frame at or before t: the next kept frame (if any) is
    // after t. Frames are kept at recorded step times, so how far back f2 lies depends on
    // the step spacing the live loop managed (a loaded, sanitized run steps tens of ms
    // apart), not on a fixed bound.
    QVERIFY(f2->t <= t_press + 1e-12);
    {
      std::size_t i2 = 0;
      while (i2 < s.frame_count() && s.frame(i2)->t <= f2->t) ++i2;
      QVERIFY(i2 > 0 && s.frame(i2 - 1)->t == f2->t);
      if (i2 < s.frame_count()) QVERIFY2(s.frame(i2)->t > t_press, qPrintable(QString::number(s.frame(i2)->t)));
    }
    double moved = 0;
    for (std::size_t i = 0; i < f0->snapshot.positions.size(); ++i)
      moved = std::max(moved, double(std::abs(f0->snapshot.positions[i] - f2->snapshot.positions[i])));
    QVERIFY2(moved > 1e-3, "the body is deformed differently at the two times");
    QVERIFY(rw.plot_points() > 100);
    // Play, pause, speed.
    rw.seek(0.0);
    rw.speed_box()->setCurrentIndex(4);
    QCOMPARE(s.speed(), 4.0);
    QElapsedTimer wall;
    wall.start();
    QTest::mouseClick(rw.play_button(), Qt::LeftButton);
    QVERIFY(s.playing());
    // The playback timer moves the time on (however slowly a loaded machine renders) ...
    QTRY_VERIFY_WITH_TIMEOUT(s.time() > 0.3, 30000);
    QTest::mouseClick(rw.play_button(), Qt::LeftButton);
    QVERIFY(!s.playing());
    const double played = s.time();
    // ... at most 4x the wall time since Play (timer-paced, never ahead of it).
    QVERIFY2(played > 0.3 && played <= 4.0 * double(wall.elapsed()) * 1e-3 + 1e-9,
             qPrintable(QString("%1 s played in %2 ms").arg(played).arg(wall.elapsed())));
    QTest::qWait(200);
    QCOMPARE(s.time(), played);  // paused
    s.set_speed(0.25);
    s.set_playing(true);
    const double t0 = s.time();
    s.advance(0.4);
    QCOMPARE(s.time(), t0 + 0.1);
    s.set_playing(false);
    // Scrubbing by clicking on the timeline.
    auto* tl = rw.timeline();
    QTest::mouseClick(tl, Qt::LeftButton, {}, QPoint(tl->x_at(s.duration() * 0.5), tl->height() / 2));
    QVERIFY(std::abs(s.time() - s.duration() * 0.5) < s.duration() / std::max(10, tl->width() - 16) * 2);
    // Events and the mark on the timeline and in the list.
    int marks = 0, changes = 0;
    for (const auto& m : s.markers()) {
      marks += m.kind == "mark";
      changes += m.kind == "parameter";
    }
    QCOMPARE(marks, 1);
    QVERIFY(changes >= 2);
    QVERIFY(rw.marker_list()->count() >= 3);
    // Export.
    const QString csv = dir_.filePath(QStringLiteral("review.csv"));
    QVERIFY(rw.export_csv(csv));
    QFile f(csv);
    QVERIFY(f.open(QIODevice::ReadOnly));
    const QList<QByteArray> lines = f.readAll().split('\n');
    QCOMPARE(lines.front(), QByteArray("t,finger,x,y,z,fx,fy,fz,fx_resim,fy_resim,fz_resim"));
    QCOMPARE(qsizetype(lines.size() - 2), qsizetype(s.recording().ticks() * 5));
    // A tick has re-simulated columns from the first recorded step on, and empty ones before
    // it (the patient loads before the simulation's first step, longer under a sanitizer).
    const double first_step = s.recording().step_times().front();
    qsizetype with_resim = 0;
    for (qsizetype i = 1; i + 1 < lines.size(); ++i) {
      const double t = lines[i].left(lines[i].indexOf(',')).toDouble();
      const bool empty = lines[i].endsWith(",,,");
      if (std::abs(t - first_step) < 1e-6) continue;  // the CSV's 9 digits cannot order these
      QVERIFY2(empty == (t < first_step), qPrintable(QStringLiteral("line %1 at %2 s (first step %3 s): %4")
                                                          .arg(i).arg(t).arg(first_step).arg(QString::fromLatin1(lines[i]))));
      with_resim += !empty;
    }
    // The scripted press ran 2.5 s at 1 kHz: at least half a second of it, all five fingers.
    QVERIFY2(with_resim >= 5 * 500, qPrintable(QString::number(with_resim)));
    const QString frames = dir_.filePath(QStringLiteral("frames"));
    QCOMPARE(rw.export_frames(frames, 0.0, 0.2, 10.0), 3);
    QImage img(QDir(frames).filePath(QStringLiteral("frame-0003.png")));
    QVERIFY(img.width() > 400 && img.height() > 300);
  }

  // The review scores the exam as `palpation score` does: the same figures and levels, the
  // coverage overlay on the skin faces pressed, the report written into a folder; a
  // recording cut short is not scored and the review says why.
  void review_scores_the_exam() {
    QVERIFY(QFileInfo::exists(rec_path_));
    const app::store::Recording rec = app::store::read_recording(rec_path_.toStdString());
    const app::train::ScoredExam want = app::train::score_recording(rec);
    int pressed = 0;
    for (unsigned char l : want.face_level) pressed += l > 0;
    QVERIFY2(pressed > 0 && want.score.coverage[0] > 0, "the scripted finger pressed on the skin");
    QCOMPARE(want.score.marks.size(), std::size_t(1));

    ui::ReviewWindow rw(std::make_unique<app::review::ReviewSession>(rec_path_.toStdString()));
    rw.show();
    QVERIFY(QTest::qWaitForWindowExposed(&rw));
    auto& s = rw.session();
    QTRY_VERIFY_WITH_TIMEOUT(s.score_ready(), 120000);
    const app::train::ScoredExam* got = s.score();
    QVERIFY2(got, s.score_error().c_str());
    QCOMPARE(got->score.hits, want.score.hits);
    QCOMPARE(got->score.false_positives, want.score.false_positives);
    QCOMPARE(got->score.tumours.size(), want.score.tumours.size());
    QCOMPARE(got->score.pattern.strips, want.score.pattern.strips);
    for (int k = 0; k < app::train::kLevels; ++k) QCOMPARE(got->score.coverage[std::size_t(k)], want.score.coverage[std::size_t(k)]);
    QVERIFY(got->face_level == want.face_level);
    // The summary names the figures.
    QTRY_VERIFY(rw.report_button()->isEnabled());
    const QString summary = rw.score_label()->text();
    QVERIFY2(summary.contains(QStringLiteral("Tumours found: %1 of %2").arg(want.score.hits).arg(want.score.tumours.size())) &&
                 summary.contains(QStringLiteral("False positives: %1").arg(want.score.false_positives)) &&
                 summary.contains(QStringLiteral("Coverage: light ")),
             qPrintable(summary));

    // The coverage at a playback time: the levels reached up to it, from the times the score
    // keeps (nothing scored again). None before the first press, more as the exam goes on,
    // never less, and at the end the whole exam's.
    QTRY_VERIFY_WITH_TIMEOUT(s.frame_at(s.time()) != nullptr, 120000);
    const std::size_t nsurf = s.frame_at(s.time())->geometry->surface.size();
    auto covered = [](const std::vector<unsigned char>& lv) { return int(std::count_if(lv.begin(), lv.end(), [](unsigned char l) { return l > 0; })); };
    const double end = s.duration();
    const std::vector<unsigned char> whole = s.surface_levels(nsurf);
    QCOMPARE(covered(whole), pressed);
    QVERIFY(s.surface_levels(nsurf, end) == whole);
    QVERIFY(*s.coverage_at(end) == want.score.coverage);
    double first = app::train::kNever, last = 0;
    for (const auto& r : want.face_reached)
      if (r[0] < app::train::kNever) {
        first = std::min(first, r[0]);
        last = std::max(last, r[0]);
      }
    QVERIFY(first < last && last <= end);
    QCOMPARE(covered(s.surface_levels(nsurf, first - 1e-6)), 0);
    QCOMPARE((*s.coverage_at(first - 1e-6))[0], 0.0);
    const double early = first + 0.25 * (last - first);
    const int covered_early = covered(s.surface_levels(nsurf, early));
    qInfo("coverage over time: %d faces at %.3f s (first press %.3f s), %d at the end (%.3f s)", covered_early, early, first,
          pressed, end);
    QVERIFY2(covered_early > 0 && covered_early < pressed, qPrintable(QString::number(covered_early)));
    QVERIFY((*s.coverage_at(early))[0] < want.score.coverage[0]);
    std::vector<unsigned char> before(nsurf, 0);
    for (int k = 0; k <= 40; ++k) {
      const auto now = s.surface_levels(nsurf, end * k / 40.0);
      for (std::size_t i = 0; i < nsurf; ++i) QVERIFY(now[i] >= before[i]);
      before = now;
    }
    QVERIFY(before == whole);

    // The overlay: hidden until toggled, then the skin faces pressed up to the playback time
    // coloured, the figures beside the toggle with it.
    rw.tick();  // the first frame's patient in the view
    QVERIFY(!rw.view()->coverage_visible());
    QVERIFY(rw.coverage_button()->isEnabled());
    rw.seek(end);
    QTest::mouseClick(rw.coverage_button(), Qt::LeftButton);
    QVERIFY(rw.coverage_button()->isChecked());
    QVERIFY(rw.view()->coverage_visible());
    auto counts = rw.view()->coverage_counts();
    QCOMPARE(counts[1] + counts[2] + counts[3], pressed);
    QVERIFY(counts[0] > pressed);  // the rest of the skin and the chest wall stay uncoloured
    QVERIFY(rw.coverage_now_label()->isVisible());
    QVERIFY2(rw.coverage_now_label()->text().contains(ui::ScoreDialog::percent(want.score.coverage[0])), qPrintable(rw.coverage_now_label()->text()));
    rw.seek(early);
    counts = rw.view()->coverage_counts();
    QCOMPARE(counts[1] + counts[2] + counts[3], covered_early);
    QVERIFY2(rw.coverage_now_label()->text().contains(ui::ScoreDialog::percent((*s.coverage_at(early))[0])),
             qPrintable(rw.coverage_now_label()->text()));
    rw.seek(0.0);
    counts = rw.view()->coverage_counts();
    QCOMPARE(counts[1] + counts[2] + counts[3], covered(s.surface_levels(nsurf, 0.0)));
    rw.seek(end);
    counts = rw.view()->coverage_counts();
    QCOMPARE(counts[1] + counts[2] + counts[3], pressed);
    QTest::mouseClick(rw.coverage_button(), Qt::LeftButton);
    QVERIFY(!rw.view()->coverage_visible());
    QVERIFY(!rw.coverage_now_label()->isVisible());

    // Save report: into the folder set here, the same score as `palpation score` writes.
    const QString out = dir_.filePath(QStringLiteral("review-report"));
    rw.set_report_folder(out);
    QTest::mouseClick(rw.report_button(), Qt::LeftButton);
    QVERIFY(QFileInfo::exists(QDir(out).filePath(QStringLiteral("report.html"))));
    QFile sj(QDir(out).filePath(QStringLiteral("score.json")));
    QVERIFY(sj.open(QIODevice::ReadOnly));
    nlohmann::json j = nlohmann::json::parse(sj.readAll().toStdString());
    QCOMPARE(j.value("recording", std::string()), rec_path_.toStdString());
    for (const char* k : {"recording", "patient", "trainee", "case"}) j.erase(k);  // what the report adds to the score
    QCOMPARE(j.dump(), app::train::to_json(want.score).dump());

    // A recording cut short (its end chunk gone): no score, and the review says why.
    const QString cut = dir_.filePath(QStringLiteral("cut.palrec"));
    {
      QFile src(rec_path_);
      QVERIFY(src.open(QIODevice::ReadOnly));
      const QByteArray all = src.readAll();
      QFile dst(cut);
      QVERIFY(dst.open(QIODevice::WriteOnly));
      dst.write(all.left(all.size() - 8));
    }
    ui::ReviewWindow cw(std::make_unique<app::review::ReviewSession>(cut.toStdString()));
    QTRY_VERIFY_WITH_TIMEOUT(cw.session().score_ready(), 120000);
    QVERIFY(!cw.session().score());
    QVERIFY(cw.session().score_error().find("cut short") != std::string::npos);
    QTRY_VERIFY(cw.score_label()->text().startsWith(QLatin1String("No score: ")));
    QVERIFY(!cw.report_button()->isEnabled() && !cw.coverage_button()->isEnabled());
    QString err;
    QVERIFY(cw.save_report(dir_.filePath(QStringLiteral("cut-report")), &err).isEmpty());
    QVERIFY(err.contains(QLatin1String("cut short")));
  }

  void corrupted_recording_is_refused() {
    auto w = make_window(dir_.filePath(QStringLiteral("second.palrec")));
    QTRY_VERIFY_WITH_TIMEOUT(w->patient_ready(), 120000);
    QVERIFY(w->library());
    const QString db = dir_.filePath(QStringLiteral("patients.sqlite"));
    const QByteArray db_before = file_hash(db);
    const std::size_t patients_before = w->library()->list().size();
    // A flipped byte in the middle of the file (inside a chunk that is followed by more).
    const QString bad = dir_.filePath(QStringLiteral("corrupted.palrec"));
    QVERIFY(QFile::copy(rec_path_, bad));
    QByteArray bytes;
    {
      QFile f(bad);
      QVERIFY(f.open(QIODevice::ReadWrite));
      bytes = f.readAll();
      bytes[bytes.size() / 2] = char(bytes[bytes.size() / 2] ^ 0x5A);
      f.seek(0);
      f.write(bytes);
    }
    const QByteArray bad_before = file_hash(bad);
    QString err;
    QVERIFY(w->open_recording(bad, &err) == nullptr);
    QVERIFY(w->review_window() == nullptr);
    QVERIFY2(err.contains(bad) && err.contains(QLatin1String("chunk")) && err.contains(QLatin1String("offset")), qPrintable(err));
    QVERIFY2(err.contains(QLatin1String("corrupted")) || err.contains(QLatin1String("checksum")), qPrintable(err));
    QCOMPARE(file_hash(bad), bad_before);  // nothing written to it
    QCOMPARE(file_hash(db), db_before);    // nor to the library
    QCOMPARE(w->library()->list().size(), patients_before);
    // The good one opens from the same window.
    QVERIFY(w->open_recording(rec_path_, &err) != nullptr);
    QVERIFY(w->review_window()->isVisible());
  }

  void patient_chooser_reaches_the_simulation() {
    auto w = make_window(dir_.filePath(QStringLiteral("third.palrec")));
    QTRY_VERIFY_WITH_TIMEOUT(w->patient_ready(), 120000);
    QVERIFY2(w->library(), qPrintable(w->library_error()));
    auto* chooser = w->patient_panel()->phantom;
    QStringList names;
    for (int i = 0; i < chooser->count(); ++i) names << chooser->itemData(i).toString();
    const auto builtins = app::store::PatientLibrary::builtin_patients();
    QVERIFY(builtins.size() >= 17);
    for (const auto& p : builtins) QVERIFY2(names.contains(QString::fromStdString(p.name)), p.name.c_str());
    QVERIFY(names.contains(QLatin1String("phantom:box")));
    // The built-in patients' descriptions (English in the library) follow the language:
    // every one differs in Japanese, and reads as stored again in English.
    auto description = [&](const std::string& name) {
      return chooser->itemData(chooser->findData(QString::fromStdString(name)), Qt::ToolTipRole).toString();
    };
    for (const auto& p : builtins) QCOMPARE(description(p.name), QString::fromStdString(p.description));
    QVERIFY(w->set_language(QStringLiteral("ja")));
    QCoreApplication::sendPostedEvents(nullptr, QEvent::LanguageChange);
    QStringList untranslated;
    for (const auto& p : builtins)
      if (description(p.name) == QString::fromStdString(p.description)) untranslated << QString::fromStdString(p.description);
    QVERIFY2(untranslated.isEmpty(), qPrintable(QStringLiteral("still English: ") + untranslated.join(QStringLiteral(" | "))));
    QCOMPARE(description("breast-small"), QStringLiteral("健康な乳房、小さめ（339 mL）、腫瘍なし"));
    QCOMPARE(description("tumour-1.0cm-mid-firm"), QStringLiteral("中くらいの乳房、硬めの腫瘍 直径 1.0 cm（107 kPa）、中心は皮膚の下 2.5 cm"));
    QVERIFY(w->set_language(QStringLiteral("en")));
    QCoreApplication::sendPostedEvents(nullptr, QEvent::LanguageChange);
    for (const auto& p : builtins) QCOMPARE(description(p.name), QString::fromStdString(p.description));

    auto& ws = w->workstation();
    const std::uint64_t gen = ws.geometry()->generation;
    const auto small = w->library()->find("breast-small");
    QVERIFY(small);
    const double height = small->body["patient"]["height"].get<double>();
    QString err;
    QVERIFY2(w->choose_patient(QStringLiteral("breast-small"), &err), qPrintable(err));
    QTRY_VERIFY_WITH_TIMEOUT(ws.geometry() && ws.geometry()->generation > gen, 120000);
    double zmax = 0;
    for (const auto& p : ws.geometry()->rest) zmax = std::max(zmax, p.z());
    QVERIFY2(std::abs(zmax - height) < 0.002, qPrintable(QStringLiteral("top %1 m, breast-small %2 m").arg(zmax).arg(height)));
    QCOMPARE(w->patient_panel()->chosen(), QStringLiteral("breast-small"));
    QCOMPARE(QSettings().value(QStringLiteral("patient/name")).toString(), QStringLiteral("breast-small"));
    QVERIFY(!w->choose_patient(QStringLiteral("no-such-patient"), &err));
    QVERIFY(err.contains(QLatin1String("no-such-patient")));
  }

  // Import scan...: a broken scan is named with its problem and nothing is saved; a good
  // one is meshed off the GUI thread, previewed, saved and then chosen like any patient.
  void import_dialog_saves_a_patient() {
    auto w = make_window(dir_.filePath(QStringLiteral("fourth.palrec")));
    QTRY_VERIFY_WITH_TIMEOUT(w->patient_ready(), 120000);
    QVERIFY(w->library());
    const std::size_t before = w->library()->list().size();
    ui::ImportDialog* d = w->open_import_dialog();
    QVERIFY(d && d->isVisible());
    const QString open = QStringLiteral(PALPATION_TEST_DATA "/open-dome.stl");
    d->file->setText(open);
    d->name->setText(QStringLiteral("scan-open"));
    d->start_import();
    QTRY_VERIFY_WITH_TIMEOUT(!d->importing(), 60000);
    QVERIFY2(d->error->text().contains(open) && d->error->text().contains(QLatin1String("open edges")), qPrintable(d->error->text()));
    QVERIFY(!d->save->isEnabled());
    QCOMPARE(w->library()->list().size(), before);

    d->file->setText(QStringLiteral(PALPATION_TEST_DATA "/dome.stl"));
    d->name->setText(QStringLiteral("scan-dome"));
    QElapsedTimer gui;
    gui.start();
    d->start_import();
    // start_import returns while the import runs on its own thread (its end comes to this
    // thread's event loop, which has not run since).
    QVERIFY2(d->importing() && gui.elapsed() < 5000,
             qPrintable(QString("start_import: importing %1 after %2 ms").arg(d->importing()).arg(gui.elapsed())));
    QTRY_VERIFY_WITH_TIMEOUT(!d->importing(), 300000);
    QVERIFY2(d->error->text().isEmpty(), qPrintable(d->error->text()));
    QVERIFY(d->save->isEnabled());
    QCOMPARE(d->progress->value(), 1000);
    QTest::mouseClick(d->save, Qt::LeftButton);
    QCOMPARE(d->saved_name(), QStringLiteral("scan-dome"));
    QCOMPARE(w->library()->list().size(), before + 1);
    QVERIFY(w->patient_panel()->phantom->findData(QStringLiteral("scan-dome")) >= 0);
    QTest::mouseClick(d->save, Qt::LeftButton);  // disabled after saving: no duplicate
    QCOMPARE(w->library()->list().size(), before + 1);
    // Chosen: the simulation runs on the imported mesh.
    const std::uint64_t gen = w->workstation().geometry()->generation;
    QString err;
    QVERIFY2(w->choose_patient(QStringLiteral("scan-dome"), &err), qPrintable(err));
    QTRY_VERIFY_WITH_TIMEOUT(w->workstation().geometry()->generation > gen, 120000);
    QVERIFY(w->workstation().stats().state != app::live::SimState::Error);
  }
};

QTEST_MAIN(TstReview)
#include "tst_review.moc"
