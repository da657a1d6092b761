// palpation-trainer: the workstation GUI.
//   palpation-trainer                       opens the window (simulated HandHIRO palpating)
//   palpation-trainer --screenshot F.png    default scene, a few seconds of scripted
//                                           palpation, saves the main window, exits
//   palpation-trainer --mode exam           starts in a training mode (instructor,
//                                           guided-practice, exam: docs/gui.md)
#include <csignal>
#include <cstdio>
#include <cstdlib>

#include <sys/socket.h>
#include <unistd.h>

#include <QApplication>
#include <QCommandLineParser>
#include <QDir>
#include <QElapsedTimer>
#include <QFileInfo>
#include <QSettings>
#include <QSocketNotifier>
#include <QTimer>
#include <QTranslator>

#include "main_window.h"
#include "review_window.h"
#include "vtk_view.h"
#include "cli/runtime_dir.h"
#include "live/patient_choice.h"
#include "live/workstation.h"

namespace {

// SIGTERM, SIGINT and SIGHUP (`kill`, Ctrl-C in the terminal, a logout) end the workstation
// as its window's close button does: the session recording gets its end chunk and the
// settings are saved, where the default action would cut the recording's last quarter
// second off. A signal handler may only do async-signal-safe things, so it writes a byte to
// a socket pair and the event loop, woken by it, closes the windows.
int g_signal_fds[2] = {-1, -1};

void on_termination_signal(int) {
  const char byte = 1;
  [[maybe_unused]] const ssize_t n = ::write(g_signal_fds[0], &byte, 1);
}

void close_on_termination_signals(QCoreApplication& app) {
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0, g_signal_fds) != 0) {
    std::perror("palpation-trainer: socketpair (SIGTERM will not save the session)");
    return;
  }
  auto* notifier = new QSocketNotifier(g_signal_fds[1], QSocketNotifier::Read, &app);
  QObject::connect(notifier, &QSocketNotifier::activated, &app, [] {
    char byte;
    while (::read(g_signal_fds[1], &byte, 1) > 0) {
    }
    std::fprintf(stderr, "palpation-trainer: ending on a termination signal\n");
    QApplication::closeAllWindows();
    QCoreApplication::quit();
  });
  struct sigaction sa {};
  sa.sa_handler = on_termination_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  for (const int s : {SIGTERM, SIGINT, SIGHUP}) ::sigaction(s, &sa, nullptr);
}

}  // namespace

int main(int argc, char** argv) {
  palpation::app::cli::set_runtime_dir();
  // VTK's OpenGL format, before the QApplication exists (stack-notes.md).
  palpation::ui::VtkView::use_default_surface_format();
  if (!std::getenv("OMP_NUM_THREADS")) setenv("OMP_NUM_THREADS", "1", 0);

  QApplication app(argc, argv);
  QApplication::setOrganizationName(QStringLiteral("palpation-trainer"));
  QApplication::setApplicationName(QStringLiteral("palpation-trainer"));
  QApplication::setApplicationVersion(QStringLiteral(PALPATION_VERSION_STRING));
  close_on_termination_signals(app);

  QCommandLineParser cli;
  cli.setApplicationDescription(QStringLiteral("Breast-cancer palpation training workstation"));
  cli.addHelpOption();
  cli.addVersionOption();
  QCommandLineOption shot(QStringLiteral("screenshot"), QStringLiteral("Render the default scene, palpate for a few seconds, save FILE.png, exit."),
                          QStringLiteral("FILE"));
  QCommandLineOption secs(QStringLiteral("seconds"), QStringLiteral("Seconds of palpation before the screenshot (default 6)."),
                          QStringLiteral("S"), QStringLiteral("6"));
  QCommandLineOption lang(QStringLiteral("language"), QStringLiteral("User interface language: en or ja."), QStringLiteral("CODE"));
  QCommandLineOption trainee(QStringLiteral("trainee"), QStringLiteral("Start in guided practice (same as --mode guided-practice)."));
  QCommandLineOption trainee_name(QStringLiteral("trainee-name"),
                                  QStringLiteral("Whose session it is: exam results are stored under this trainee in the patient "
                                                 "library (added when new)."),
                                  QStringLiteral("NAME"));
  QCommandLineOption mode(QStringLiteral("mode"), QStringLiteral("Training mode to start in: instructor (default), guided-practice or exam."),
                          QStringLiteral("MODE"));
  QCommandLineOption stereo(QStringLiteral("stereo"), QStringLiteral("mono, anaglyph, side-by-side or interlaced."), QStringLiteral("MODE"));
  QCommandLineOption resolution(QStringLiteral("resolution"),
                                QStringLiteral("Breast resolution: coarse, paper or fine (default: paper where a GPU steps the "
                                               "simulation, else coarse)."),
                                QStringLiteral("NAME"));
  QCommandLineOption device(QStringLiteral("device"),
                            QStringLiteral("simulated (default: scripted hand, mouse palpation), emulator (HandHIRO protocol to an "
                                           "in-process emulator over loopback UDP) or handhiro (the robot, see --robot)."),
                            QStringLiteral("KIND"), QStringLiteral("simulated"));
  QCommandLineOption robot(QStringLiteral("robot"), QStringLiteral("HandHIRO address ADDRESS:PORT (default: resources/handhiro.json's)."),
                           QStringLiteral("ADDRESS:PORT"));
  QCommandLineOption review(QStringLiteral("review"), QStringLiteral("Review a session recording (no live session)."),
                            QStringLiteral("RECORDING"));
  QCommandLineOption review_at(QStringLiteral("review-at"), QStringLiteral("With --review --screenshot: the time (s) to show."),
                               QStringLiteral("T"));
  QCommandLineOption record(QStringLiteral("record"), QStringLiteral("Record the session into FILE (default: a new file in the "
                                                                     "recordings folder)."),
                            QStringLiteral("FILE"));
  QCommandLineOption case_file(QStringLiteral("case"),
                               QStringLiteral("Examine this case: a scenario file (palpation case generate) as the patient."),
                               QStringLiteral("FILE"));
  cli.addOptions({shot, secs, lang, trainee, trainee_name, mode, stereo, resolution, device, robot, review, review_at, record, case_file});
  cli.process(app);

  if (cli.isSet(review)) {
    // Review mode alone: a student's machine needs no device and no live simulation.
    std::unique_ptr<palpation::app::review::ReviewSession> session;
    try {
      session = std::make_unique<palpation::app::review::ReviewSession>(cli.value(review).toStdString());
    } catch (const std::exception& e) {
      std::fprintf(stderr, "palpation-trainer: %s\n", e.what());
      return 2;
    }
    // The language as the workstation chooses it: --language, else the stored choice
    // (MainWindow::set_language's setting); screenshots English unless asked.
    QTranslator translator;
    const QString code = cli.isSet(lang)   ? cli.value(lang)
                         : cli.isSet(shot) ? QStringLiteral("en")
                                           : QSettings().value(QStringLiteral("language"), QStringLiteral("en")).toString();
    if (code != QLatin1String("en")) {
      if (translator.load(QStringLiteral(":/i18n/palpation_%1.qm").arg(code))) QCoreApplication::installTranslator(&translator);
      else std::fprintf(stderr, "palpation-trainer: no \"%s\" translation: English\n", qPrintable(code));
    }
    palpation::ui::ReviewWindow rw(std::move(session));
    rw.show();
    if (cli.isSet(shot)) {
      const QString file = cli.value(shot);
      const double at = cli.isSet(review_at) ? cli.value(review_at).toDouble() : -1.0;
      auto* t = new QTimer(&rw);
      t->start(100);
      QObject::connect(t, &QTimer::timeout, &rw, [&rw, t, file, at]() {
        auto& s = rw.session();
        if (!s.finished()) return;
        t->stop();
        rw.seek(at >= 0 ? at : s.duration() * 0.5);
        rw.tick();
        QTimer::singleShot(300, &rw, [&rw, file]() {
          const QImage img = palpation::ui::VtkView::grab_with_views(&rw);
          const bool ok = img.save(file);
          const auto c = rw.session().compare();
          std::fprintf(stderr, "palpation-trainer: %s %s (%dx%d); re-simulated %zu of %zu, largest difference %.3g N\n",
                       ok ? "saved" : "could not save", qPrintable(file), img.width(), img.height(), rw.session().done(),
                       rw.session().total(), c.max_diff);
          QApplication::exit(ok ? 0 : 1);
        });
      });
    }
    return app.exec();
  }

  palpation::app::live::WorkstationOptions opt;
  opt.scenario = palpation::app::live::default_workstation_scenario();
  const std::string res = cli.isSet(resolution) ? cli.value(resolution).toStdString() : palpation::app::live::default_resolution();
  if (!palpation::app::live::set_phantom_resolution(opt.scenario, res)) {
    std::fprintf(stderr, "palpation-trainer: --resolution: unknown level \"%s\" (coarse, paper, fine)\n", res.c_str());
    return 2;
  }
  if (!cli.isSet(resolution) && !cli.isSet(shot)) {  // screenshots: always the default scene
    // The last patient's resolution (QSettings), when it names a known level.
    const std::string last = QSettings().value(QStringLiteral("patient/resolution")).toString().toStdString();
    palpation::app::live::set_phantom_resolution(opt.scenario, last);
  }
  if (cli.isSet(case_file)) {
    try {
      opt.scenario = palpation::app::live::case_patient(cli.value(case_file).toStdString(), res);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "palpation-trainer: --case: %s\n", e.what());
      return 2;
    }
  }
  opt.device = cli.value(device).toStdString();
  if (cli.isSet(robot)) {
    const QString r = cli.value(robot);
    const int colon = int(r.lastIndexOf(QLatin1Char(':')));
    bool ok = colon > 0;
    const int port = ok ? r.mid(colon + 1).toInt(&ok) : 0;
    if (!ok || port <= 0 || port > 65535) {
      std::fprintf(stderr, "palpation-trainer: --robot: expected ADDRESS:PORT, got \"%s\"\n", qPrintable(r));
      return 2;
    }
    opt.robot_address = r.left(colon).toStdString();
    opt.robot_port = port;
  }
  auto training = cli.isSet(trainee) ? palpation::app::live::TrainingMode::GuidedPractice : palpation::app::live::TrainingMode::Instructor;
  if (cli.isSet(mode)) {
    const auto m = palpation::app::live::training_mode_from_name(cli.value(mode).toStdString());
    if (!m) {
      std::fprintf(stderr, "palpation-trainer: --mode: unknown mode \"%s\" (instructor, guided-practice, exam)\n", qPrintable(cli.value(mode)));
      return 2;
    }
    training = *m;
  }
  std::unique_ptr<palpation::app::live::Workstation> ws;
  try {
    ws = std::make_unique<palpation::app::live::Workstation>(opt);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "palpation-trainer: %s\n", e.what());
    return 2;
  }
  palpation::ui::MainWindow w(std::move(ws), nullptr, cli.isSet(record) ? cli.value(record) : QString(), training);
  if (cli.isSet(trainee_name)) w.set_trainee_name(cli.value(trainee_name));
  if (cli.isSet(case_file)) w.set_case_name(QFileInfo(cli.value(case_file)).completeBaseName());
  if (!cli.isSet(resolution) && !cli.isSet(shot) && !cli.isSet(case_file)) {
    // The last patient chosen (QSettings), when the library still has it.
    const QString last = QSettings().value(QStringLiteral("patient/name")).toString();
    if (!last.isEmpty() && last.toStdString() != opt.scenario.source) {
      QString err;
      if (!w.choose_patient(last, &err)) std::fprintf(stderr, "palpation-trainer: last patient not loaded: %s\n", qPrintable(err));
    }
  }
  // Screenshots show the default scene: English, mono, whatever the stored settings say.
  if (cli.isSet(lang)) w.set_language(cli.value(lang));
  else if (cli.isSet(shot)) w.set_language(QStringLiteral("en"));
  if (cli.isSet(shot) && !cli.isSet(stereo)) w.view()->set_stereo(palpation::ui::VtkView::Stereo::Mono);
  if (cli.isSet(stereo)) {
    const QString s = cli.value(stereo);
    using S = palpation::ui::VtkView::Stereo;
    w.view()->set_stereo(s == QLatin1String("anaglyph") ? S::Anaglyph
                         : s == QLatin1String("side-by-side") ? S::SideBySide
                         : s == QLatin1String("interlaced") ? S::Interlaced
                                                            : S::Mono);
  }
  if (cli.isSet(shot)) {
    // Screenshots are for docs and checks: a fixed window size, the stored layout ignored.
    w.resize(1400, 900);
  }
  w.show();
  if (cli.isSet(shot)) {
    const QString file = cli.value(shot);
    const int ms = int(cli.value(secs).toDouble() * 1000);
    auto* t = new QTimer(&w);
    QElapsedTimer since_ready;
    t->start(100);
    QObject::connect(t, &QTimer::timeout, &w, [&w, &since_ready, file, ms]() {
      if (!w.patient_ready()) return;  // meshing/loading first
      if (!since_ready.isValid()) since_ready.start();
      if (since_ready.elapsed() < ms) return;
      const QImage img = palpation::ui::VtkView::grab_with_views(&w);
      const bool ok = img.save(file);
      const auto& s = w.workstation().stats();
      std::fprintf(stderr,
                   "palpation-trainer: %s %s (%dx%d); view %.0f fps (paint %.1f ms/frame: render %.1f, swap %.1f; snapshot "
                   "%.2f ms), simulation %.0f Hz, haptic %.0f Hz\n",
                   ok ? "saved" : "could not save", qPrintable(file), img.width(), img.height(), w.frame_rate(),
                   w.view()->paint_ms(), w.view()->render_ms(), w.view()->swap_ms(), w.view()->update_ms(), s.step_rate_hz,
                   s.haptic_rate_hz);
      std::fprintf(stderr, "palpation-trainer: OpenGL renderer \"%s\"%s; %s rendering style\n",
                   qPrintable(w.view()->gl_renderer()), w.view()->software_renderer() ? " (software)" : "",
                   w.view()->light_style() ? "light (fast)" : "full");
      if (qEnvironmentVariableIsSet("PALPATION_BENCH_VIEW")) {
        // docs/gui.md: the view's own cost. The simulation stopped (its core free), the
        // last snapshot drawn N times back to back, each a full frame of the view as it is
        // presented live (VTK render, blit into the view's native window, swap: the X
        // server gets the view's pixels; the rest of the window is not redrawn per frame,
        // live or here), with the event loop run between frames as live.
        w.workstation().stop();
        const int n = std::max(1, qEnvironmentVariableIntValue("PALPATION_BENCH_VIEW"));
        if (!w.view()->render_now()) std::fprintf(stderr, "palpation-trainer: view alone: the view is not on screen\n");
        const quint64 f0 = w.view()->frames();
        const double p0 = w.view()->paint_ms() * double(f0), r0 = w.view()->render_ms() * double(f0),
                     s0 = w.view()->swap_ms() * double(f0);
        QElapsedTimer bench;
        bench.start();
        for (int i = 0; i < n; ++i) {
          w.view()->render_now();
          QCoreApplication::processEvents();
        }
        const double repaint_ms = double(bench.nsecsElapsed()) * 1e-6 / n;
        const double fn = double(w.view()->frames() - f0);
        const double frame_ms = fn > 0 ? (w.view()->paint_ms() * double(w.view()->frames()) - p0) / fn : 0;
        const double in_render = fn > 0 ? (w.view()->render_ms() * double(w.view()->frames()) - r0) / fn : 0;
        const double in_swap = fn > 0 ? (w.view()->swap_ms() * double(w.view()->frames()) - s0) / fn : 0;
        const double render_ms = w.view()->bench_render(n);
        std::fprintf(stderr,
                     "palpation-trainer: view alone: %.1f ms per frame presented (%.0f fps; %d frames; a frame %.1f ms: "
                     "render %.1f, blit %.1f, swap %.1f; the event loop %.1f); VTK's render alone (glFinish) %.1f ms\n",
                     repaint_ms, 1000.0 / repaint_ms, n, frame_ms, in_render, frame_ms - in_render - in_swap, in_swap,
                     repaint_ms - frame_ms, render_ms);
      }
      QApplication::exit(ok ? 0 : 1);
    });
  }
  return app.exec();
}
