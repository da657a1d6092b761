// A trainee's progress series (app/train/progress.h): one point per exam in the results'
// order, figures copied as stored, exams without tumours left out of the sensitivity and
// deep-over-tumour series only; the date of a result's start.
#include <QtTest>

#include "train/progress.h"

using namespace palpation::app;

class TstProgress : public QObject {
  Q_OBJECT

 private slots:
  void series_over_sessions() {
    std::vector<store::ExamResult> r(3);
    r[0].started = "2026-11-20T09:00:00Z";
    r[0].sensitivity = 0.5;
    r[0].false_positives = 2;
    r[0].coverage_light = 0.4;
    r[0].coverage_medium = 0.3;
    r[0].coverage_deep = 0.1;
    r[0].deep_reached = 0.0;
    r[0].exam_time = 120;
    r[1].started = "2026-11-21T09:00:00Z";  // a healthy case: no sensitivity
    r[1].false_positives = 1;
    r[1].coverage_light = 0.7;
    r[1].exam_time = 150;
    r[2].started = "2026-11-22T09:00:00Z";
    r[2].sensitivity = 1.0;
    r[2].coverage_light = 0.9;
    r[2].coverage_medium = 0.8;
    r[2].coverage_deep = 0.6;
    r[2].deep_reached = 1.0;
    r[2].exam_time = 200;
    const auto s = train::progress_series(r);
    QCOMPARE(s.sessions, 3);
    QCOMPARE(s.sensitivity.session, (std::vector<double>{1, 3}));
    QCOMPARE(s.sensitivity.value, (std::vector<double>{0.5, 1.0}));
    QCOMPARE(s.deep_reached.session, (std::vector<double>{1, 3}));
    QCOMPARE(s.false_positives.value, (std::vector<double>{2, 1, 0}));
    QCOMPARE(s.coverage[0].value, (std::vector<double>{0.4, 0.7, 0.9}));
    QCOMPARE(s.coverage[1].value, (std::vector<double>{0.3, 0.0, 0.8}));
    QCOMPARE(s.coverage[2].session, (std::vector<double>{1, 2, 3}));
    QCOMPARE(s.exam_time.value, (std::vector<double>{120, 150, 200}));
    QCOMPARE(train::result_date(r[1]), std::string("2026-11-21"));
    QCOMPARE(train::progress_series({}).sessions, 0);
  }
};

QTEST_GUILESS_MAIN(TstProgress)
#include "tst_progress.moc"
