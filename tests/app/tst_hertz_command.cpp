// `palpation hertz` (app/cli/cmd_hertz.cpp): one row per element, Poisson's ratio and
// mesh, the exit code following --limit, hertz.json, bad input refused. The physics of
// the indentation itself is tst_hertz's (sim/hertz_probe.h); the mesh here is 12 cells
// across, far from converged, so the rows are tens of percent off Hertz (measured: linear
// +67 % at nu 0.45, +156 % at 0.49; nodal pressure +29 %, +32 %).
#include <QtTest>

#include <QDir>
#include <QFile>

#include <nlohmann/json.hpp>

#include "cli_run.h"

class TestHertzCommand : public QObject {
  Q_OBJECT
 private slots:
  void rowsLimitAndJson() {
    const QString dir = QDir::temp().filePath("tst_hertz_command");
    QDir(dir).removeRecursively();
    const QStringList base{"hertz", "--cells", "12", "--nu", "0.45,0.49", "--elements", "linear,nodal-pressure"};
    // Tens of percent off Hertz: a 5 % limit fails, a 500 % one passes.
    const CliRun off = run_palpation(base + QStringList{"--limit", "0.05"});
    QCOMPARE(off.code, 1);
    QVERIFY2(off.out.contains("OFF"), qPrintable(off.out));
    const CliRun ok = run_palpation(base + QStringList{"--limit", "5", "--out", dir});
    QVERIFY2(ok.code == 0, qPrintable(ok.err));
    QFile f(dir + "/hertz.json");
    QVERIFY(f.open(QIODevice::ReadOnly));
    const auto j = nlohmann::json::parse(f.readAll().toStdString());
    QCOMPARE(int(j["rows"].size()), 4);  // 2 elements x 2 ratios x 1 mesh
    for (const auto& r : j["rows"]) {
      QVERIFY(r["ok"].get<bool>());
      QVERIFY(r["force"].get<double>() > 0 && r["hertz"].get<double>() > 0);
      QCOMPARE(r["error"].get<double>(), r["force"].get<double>() / r["hertz"].get<double>() - 1);
      // All the steps' CG iterations: more than the hardest step's alone (30 steps press).
      QVERIFY(r["max_cg_iterations"].get<long>() > 0 && r["cg_iterations"].get<long>() > r["max_cg_iterations"].get<long>());
      QCOMPARE(r["multigrid_smoother"].get<std::string>(), std::string("none"));  // block-Jacobi: no levels
    }
    // The nodal-pressure element does not lock: softer than the linear one at the same
    // ratio and mesh, and far less so than it as nu goes from 0.45 to 0.49.
    for (int k = 0; k < 2; ++k) QVERIFY(j["rows"][2 + k]["force"].get<double>() < j["rows"][k]["force"].get<double>());
    const double linear_rise = j["rows"][1]["force"].get<double>() / j["rows"][0]["force"].get<double>();
    const double nodal_rise = j["rows"][3]["force"].get<double>() / j["rows"][2]["force"].get<double>();
    QVERIFY2(nodal_rise < 1.2 && linear_rise > 1.4, qPrintable(QString("%1 %2").arg(linear_rise).arg(nodal_rise)));
    QDir(dir).removeRecursively();
  }

  void badInputIsRefused() {
    for (const QStringList& args : {QStringList{"hertz", "--nu", "0.5"}, QStringList{"hertz", "--elements", "quadratic"},
                                    QStringList{"hertz", "--cells", "2"}}) {
      const CliRun r = run_palpation(args);
      QVERIFY2(r.code == 2, qPrintable(args.join(' ') + ": " + QString::number(r.code)));
      QVERIFY2(!r.err.trimmed().isEmpty(), qPrintable(args.join(' ')));
    }
  }
};

QTEST_APPLESS_MAIN(TestHertzCommand)
#include "tst_hertz_command.moc"
