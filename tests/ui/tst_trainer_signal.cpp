// The workstation program ended by a signal (`kill`, Ctrl-C, a logout): SIGTERM, SIGINT
// and SIGHUP close it as its window's close button does, so the session recording it was
// writing is complete (its end chunk written), not cut off at the last written chunk.
#include <QtTest>

#include <csignal>

#include <QProcess>
#include <QTemporaryDir>

#include "store/recording.h"

using namespace palpation::app;

class TestTrainerSignal : public QObject {
  Q_OBJECT

 private slots:
  void endsCleanlyOnASignal_data() {
    QTest::addColumn<int>("signal");
    QTest::newRow("SIGTERM") << int(SIGTERM);
    QTest::newRow("SIGINT") << int(SIGINT);
    QTest::newRow("SIGHUP") << int(SIGHUP);
  }

  void endsCleanlyOnASignal() {
    QFETCH(int, signal);
    QTemporaryDir dir;
    QVERIFY(dir.isValid());
    const QString rec = dir.filePath(QStringLiteral("session.palrec"));
    QProcess p;
    QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
    // A user of its own: settings, patient library and recordings in the temporary folder.
    env.insert(QStringLiteral("HOME"), dir.path());
    env.insert(QStringLiteral("XDG_CONFIG_HOME"), dir.filePath(QStringLiteral("config")));
    env.insert(QStringLiteral("XDG_DATA_HOME"), dir.filePath(QStringLiteral("data")));
    env.insert(QStringLiteral("PALPATION_DB"), dir.filePath(QStringLiteral("patients.sqlite")));
    env.insert(QStringLiteral("PALPATION_RECORDINGS"), dir.filePath(QStringLiteral("recordings")));
    p.setProcessEnvironment(env);
    p.setProcessChannelMode(QProcess::MergedChannels);
    // The screenshot would end it after 10 minutes: the signal comes long before.
    p.start(QStringLiteral(PALPATION_TRAINER_EXE),
            {QStringLiteral("--record"), rec, QStringLiteral("--screenshot"), dir.filePath(QStringLiteral("never.png")),
             QStringLiteral("--seconds"), QStringLiteral("600")});
    QVERIFY(p.waitForStarted(30000));
    // Running and recording: the file grows past its header (chunks every 0.25 s).
    const auto size = [&] { return QFileInfo(rec).size(); };
    QTRY_VERIFY_WITH_TIMEOUT(size() > 0, 120000);
    const qint64 first = size();
    QTRY_VERIFY_WITH_TIMEOUT(size() > first, 60000);
    QCOMPARE(p.state(), QProcess::Running);
    QCOMPARE(::kill(pid_t(p.processId()), signal), 0);
    QVERIFY2(p.waitForFinished(60000), "the trainer did not end within 60 s of the signal");
    const QString out = QString::fromLocal8Bit(p.readAll());
    QVERIFY2(p.exitStatus() == QProcess::NormalExit, qPrintable(out));
    QVERIFY2(p.exitCode() == 0, qPrintable(out));
    QVERIFY2(out.contains(QStringLiteral("ending on a termination signal")), qPrintable(out));
    QVERIFY(!QFileInfo::exists(dir.filePath(QStringLiteral("never.png"))));
    const store::Recording r = store::read_recording(rec.toStdString());
    QVERIFY2(r.complete, r.interrupted.c_str());
    QVERIFY(!r.recovered);
    QVERIFY(r.ticks() > 0);
  }
};

QTEST_GUILESS_MAIN(TestTrainerSignal)
#include "tst_trainer_signal.moc"
