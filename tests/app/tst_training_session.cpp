// The training modes (app/live/training_session.h) without a window or a simulation: mode
// names, which changes take an instructor's confirmation, the anonymous case code, which
// events a trainee may read, the session's exam (started by a trainee mode, ended once,
// listeners told, marks refused after it), and the events as data: a mark's confidence
// (text and JSON; a mark of an older recording reads as certain) and the exam's end.
#include <QtTest>

#include "live/event.h"
#include "live/training_session.h"
#include "live/workstation.h"

using namespace palpation;
using app::live::Event;
using app::live::EventKind;
using app::live::ModeChange;
using app::live::TrainingMode;
using app::live::TrainingSession;

class TstTrainingSession : public QObject {
  Q_OBJECT

 private slots:
  void mode_names() {
    for (TrainingMode m : {TrainingMode::Instructor, TrainingMode::GuidedPractice, TrainingMode::Exam})
      QVERIFY(app::live::training_mode_from_name(app::live::training_mode_name(m)) == m);
    QCOMPARE(std::string(app::live::training_mode_name(TrainingMode::GuidedPractice)), std::string("guided-practice"));
    QVERIFY(!app::live::training_mode_from_name("trainee"));
    QVERIFY(!app::live::is_trainee(TrainingMode::Instructor));
    QVERIFY(app::live::is_trainee(TrainingMode::Exam));
  }

  void confirmation_rule() {
    using app::live::needs_instructor_confirmation;
    // Back to Instructor from a trainee mode: always, whether the exam runs or ended.
    QVERIFY(needs_instructor_confirmation(TrainingMode::Exam, TrainingMode::Instructor, true));
    QVERIFY(needs_instructor_confirmation(TrainingMode::Exam, TrainingMode::Instructor, false));
    QVERIFY(needs_instructor_confirmation(TrainingMode::GuidedPractice, TrainingMode::Instructor, true));
    // Out of a running exam into practice; not out of an ended one, nor out of practice.
    QVERIFY(needs_instructor_confirmation(TrainingMode::Exam, TrainingMode::GuidedPractice, true));
    QVERIFY(!needs_instructor_confirmation(TrainingMode::Exam, TrainingMode::GuidedPractice, false));
    QVERIFY(!needs_instructor_confirmation(TrainingMode::GuidedPractice, TrainingMode::Exam, true));
    // Into a trainee mode, or staying: never.
    QVERIFY(!needs_instructor_confirmation(TrainingMode::Instructor, TrainingMode::Exam, false));
    QVERIFY(!needs_instructor_confirmation(TrainingMode::Instructor, TrainingMode::GuidedPractice, false));
    QVERIFY(!needs_instructor_confirmation(TrainingMode::Exam, TrainingMode::Exam, true));
  }

  void anonymous_case_code() {
    const std::string name = "tumour-2.0cm-deep-hard";
    const std::string code = app::live::anonymous_case_code(name);
    QCOMPARE(code, app::live::anonymous_case_code(name));  // stable
    QVERIFY2(code.size() == 6 && code.rfind("C-", 0) == 0, code.c_str());
    for (const char* part : {"tumour", "2.0", "deep", "hard"}) QVERIFY(code.find(part) == std::string::npos);
    QVERIFY(code != app::live::anonymous_case_code("tumour-2.0cm-deep-soft"));
    QVERIFY(code != app::live::anonymous_case_code("phantom:breast"));
  }

  void events_a_trainee_reads() {
    app::live::MaterialEdit add;
    add.kind = app::live::MaterialEdit::Kind::AddTumour;
    QVERIFY(!app::live::shown_to_trainee(Event::material(add)));
    QVERIFY(!app::live::shown_to_trainee(Event::patient_loading("tumour-2.0cm-deep-hard")));
    QVERIFY(!app::live::shown_to_trainee(Event::patient_loaded(10, 20, "cpu")));
    QVERIFY(!app::live::shown_to_trainee(Event::params()));
    QVERIFY(app::live::shown_to_trainee(Event::trainee_mark(1)));
    QVERIFY(app::live::shown_to_trainee(Event::mode_change(ModeChange::Exam)));
    QVERIFY(app::live::shown_to_trainee(Event::exam_ended(ModeChange::Exam)));
  }

  void session_exam() {
    app::live::WorkstationOptions opt;
    opt.scenario = app::live::default_workstation_scenario();
    opt.haptic_priority = 0;
    app::live::Workstation ws(opt);  // not started: no threads, events only

    TrainingSession s(ws);
    QCOMPARE(s.mode(), TrainingMode::Instructor);
    QVERIFY(!s.exam_running());
    QVERIFY(s.accepts_marks());
    QVERIFY(!s.end_exam());  // none running: nothing logged
    QVERIFY(ws.events().empty());

    int told = 0;
    s.add_exam_end_listener([&](const Event& e) {
      ++told;
      QCOMPARE(e.kind, EventKind::ExamEnded);
    });
    s.set_mode(TrainingMode::Exam);
    QVERIFY(s.exam_running());
    QVERIFY(s.needs_confirmation(TrainingMode::Instructor));
    QVERIFY(s.needs_confirmation(TrainingMode::GuidedPractice));
    auto ev = ws.events();
    QCOMPARE(ev.size(), std::size_t(1));
    QCOMPARE(ev[0].kind, EventKind::Mode);
    QCOMPARE(ev[0].mode, ModeChange::Exam);

    QVERIFY(s.end_exam());
    QVERIFY(!s.end_exam());  // once
    QCOMPARE(told, 1);
    QVERIFY(!s.exam_running());
    QVERIFY(!s.accepts_marks());
    QCOMPARE(s.mode(), TrainingMode::Exam);  // the answer stays hidden until the instructor returns
    ev = ws.events();
    QCOMPARE(ev.size(), std::size_t(2));
    QCOMPARE(ev[1].kind, EventKind::ExamEnded);
    QCOMPARE(ev[1].mode, ModeChange::Exam);

    // A new practice starts; leaving it for Instructor ends it first (logged), then the mode.
    s.set_mode(TrainingMode::GuidedPractice);
    QVERIFY(s.exam_running());
    s.set_mode(TrainingMode::Instructor);
    QVERIFY(!s.exam_running());
    QCOMPARE(told, 2);
    ev = ws.events();
    QCOMPARE(ev.size(), std::size_t(5));
    QCOMPARE(ev[2].mode, ModeChange::GuidedPractice);
    QCOMPARE(ev[3].kind, EventKind::ExamEnded);
    QCOMPARE(ev[3].mode, ModeChange::GuidedPractice);
    QCOMPARE(ev[4].kind, EventKind::Mode);
    QCOMPARE(ev[4].mode, ModeChange::Instructor);

    s.set_mark_confidence(1.7);
    QCOMPARE(s.mark_confidence(), 1.0);
    s.set_mark_confidence(0.25);
    QCOMPARE(s.mark_confidence(), 0.25);

    // Started in a trainee mode: the exam runs from the start.
    TrainingSession exam(ws, TrainingMode::Exam);
    QVERIFY(exam.exam_running());
  }

  void mark_confidence_as_data() {
    const Event e = Event::trainee_mark(2, Eigen::Vector3d(0.125, 0, 0.06), "hard", 0.5);
    QCOMPARE(QString::fromStdString(e.text()), QStringLiteral("trainee mark 2 at (12.5, 0.0, 6.0) cm, 50 % confident: hard"));
    const auto back = app::live::event_from_json(app::live::event_kind_name(e.kind), app::live::event_args_json(e));
    QVERIFY(back);
    QCOMPARE(back->confidence, 0.5);
    QCOMPARE(back->text(), e.text());
    // Certain: the text of marks before they had a confidence.
    QCOMPARE(QString::fromStdString(Event::trainee_mark(1).text()), QStringLiteral("trainee mark 1"));
    // A recording's mark without a confidence: certain.
    const auto old = app::live::event_from_json("mark", nlohmann::json{{"mark", 3}});
    QVERIFY(old);
    QCOMPARE(old->confidence, 1.0);
    QVERIFY(!app::live::event_from_json("mark", nlohmann::json{{"mark", 3}, {"confidence", "high"}}));

    const Event end = Event::exam_ended(ModeChange::Exam);
    QCOMPARE(std::string(app::live::event_kind_name(end.kind)), std::string("exam-ended"));
    QCOMPARE(end.text(), std::string("exam ended"));
    const auto end_back = app::live::event_from_json("exam-ended", app::live::event_args_json(end));
    QVERIFY(end_back && end_back->kind == EventKind::ExamEnded && end_back->mode == ModeChange::Exam);
    // Recordings keep reading the one trainee mode of before.
    const auto trainee = app::live::event_from_json("mode", nlohmann::json{{"mode", "trainee"}});
    QVERIFY(trainee && trainee->mode == ModeChange::Trainee);
  }
};

QTEST_MAIN(TstTrainingSession)
#include "tst_training_session.moc"
