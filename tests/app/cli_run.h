// The palpation command line (PALPATION_EXE, the test's compile definition) run as a child
// process, as a user runs it: its exit code (-1 when it crashed or did not finish) and its
// standard output and error; in the test's environment unless given another.
#pragma once

#include <QProcess>
#include <QString>
#include <QStringList>

struct CliRun {
  int code = -1;
  QString out, err;
};

inline CliRun run_palpation(const QStringList& args,
                            const QProcessEnvironment& env = QProcessEnvironment::systemEnvironment(),
                            int timeout_ms = 600000) {
  QProcess p;
  p.setProcessEnvironment(env);
  p.start(PALPATION_EXE, args);
  const bool finished = p.waitForFinished(timeout_ms);
  return {finished && p.exitStatus() == QProcess::NormalExit ? p.exitCode() : -1,
          QString::fromUtf8(p.readAllStandardOutput()), QString::fromUtf8(p.readAllStandardError())};
}
