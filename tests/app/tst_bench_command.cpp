// `palpation bench --series` (app/cli/bench.cpp): every step of every point in series.csv,
// the warm-up marked, agreeing with the point's own row in bench.csv; --series without
// --out refused. Run as a user runs it (a child process) on the coarse breast, CPU.
#include <QtTest>

#include <QDir>
#include <QFile>

#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "cli/bench.h"
#include "cli_run.h"
#include "live/headless_run.h"

namespace {

std::vector<QStringList> csv_rows(const QString& path) {
  QFile f(path);
  std::vector<QStringList> rows;
  if (!f.open(QIODevice::ReadOnly)) return rows;
  for (const QByteArray& line : f.readAll().split('\n'))
    if (!line.isEmpty()) rows.push_back(QString::fromUtf8(line).split(','));
  return rows;
}

}  // namespace

class TestBenchCommand : public QObject {
  Q_OBJECT
 private slots:
  void seriesHoldsEveryStep() {
    const QString dir = QDir::temp().filePath("tst_bench_command");
    QDir(dir).removeRecursively();
    constexpr int kSteps = 80;
    const CliRun r = run_palpation({"bench", "--meshes", "coarse", "--backends", "cpu", "--precisions", "double",
                                    "--tolerances", "1e-3,1e-2", "--steps", QString::number(kSteps), "--series", "--out", dir});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    const auto series = csv_rows(dir + "/series.csv");
    const auto bench = csv_rows(dir + "/bench.csv");
    QVERIFY(!series.empty() && bench.size() == 3);  // a header and two points
    QCOMPARE(series[0].join(','), QString(palpation::app::cli::kSeriesHeader));
    QCOMPARE(int(series.size()), 1 + 2 * kSteps);
    const QStringList head = series[0], bhead = bench[0];
    const auto col = [&](const QString& name) { return int(head.indexOf(name)); };
    const auto bcol = [&](const QString& name) { return int(bhead.indexOf(name)); };
    // Per point (the setting column): its steps in order, the first kWarmupSteps not timed,
    // and what bench.csv says of the point read back from them.
    std::map<QString, std::vector<QStringList>> by;
    for (std::size_t k = 1; k < series.size(); ++k) by[series[k][col("setting")]].push_back(series[k]);
    QCOMPARE(int(by.size()), 2);
    for (std::size_t b = 1; b < bench.size(); ++b) {
      const double tol = bench[b][bcol("cg_tolerance")].toDouble();
      const QString setting = QString::asprintf("%.0e", tol);
      QVERIFY2(by.count(setting), qPrintable(setting));
      const auto& rows = by[setting];
      QCOMPARE(int(rows.size()), kSteps);
      std::vector<double> timed;
      int itmax = 0;
      for (int k = 0; k < kSteps; ++k) {
        QCOMPARE(rows[k][col("step")].toInt(), k);
        QCOMPARE(rows[k][col("timed")].toInt(), k >= int(palpation::app::live::kWarmupSteps) ? 1 : 0);
        const double ms = rows[k][col("step_ms")].toDouble();
        QVERIFY(ms > 0);
        if (k >= int(palpation::app::live::kWarmupSteps)) timed.push_back(ms);
        itmax = std::max(itmax, rows[k][col("cg_iterations")].toInt());
        // A fixed tolerance (no error controller) is the one in force at every step.
        QCOMPARE(rows[k][col("cg_tolerance")].toDouble(), tol);
      }
      // The largest CG count is over every step, the median step time over the timed ones.
      QCOMPARE(itmax, bench[b][bcol("cg_iterations_max")].toInt());
      const double median = bench[b][bcol("step_ms_median")].toDouble();
      QVERIFY(median >= *std::min_element(timed.begin(), timed.end()) && median <= *std::max_element(timed.begin(), timed.end()));
      // The press reaches the skin within the window: some steps in contact.
      QVERIFY(std::any_of(rows.begin(), rows.end(), [&](const QStringList& row) { return row[col("contacts")].toInt() > 0; }));
    }
    QDir(dir).removeRecursively();
  }

  void seriesNeedsAnOutputFolder() {
    const CliRun r = run_palpation({"bench", "--quick", "--series"});
    QVERIFY2(r.code == 2, qPrintable(QString::number(r.code)));
    QVERIFY2(r.err.contains("--out"), qPrintable(r.err));
  }
};

QTEST_APPLESS_MAIN(TestBenchCommand)
#include "tst_bench_command.moc"
