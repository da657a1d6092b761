// A classroom sharing one library (docs/patient-library.md, "PostgreSQL"): several stations
// opening, importing, adding trainees, recording sessions and storing results at once (on
// SQLite and, with PALPATION_TEST_PG, on a PostgreSQL server); a server that goes away
// mid-session (a clear message naming it, the result kept on the station with its
// recording, nothing lost), and comes back (the kept results sent once, the library usable
// again without reopening it). The server's going away is a relay between the stations and
// the server that is closed (every connection cut, new ones refused) and opened again on
// the same port; a server restart is the server ending the station's connection.
#include <QtTest>

#include <QHostAddress>
#include <QRegularExpression>
#include <QMutex>
#include <QTcpServer>
#include <QTcpSocket>
#include <QThread>

#include <filesystem>
#include <fstream>
#include <set>
#include <thread>

#include "scenario.h"
#include "store/patient_library.h"
#include "store/recording.h"
#include "test_databases.h"

using namespace palpation;
using namespace palpation::app::store;
namespace fs = std::filesystem;

namespace {

// Forwards TCP connections from a local port to the server, in a thread of its own.
class Relay : public QObject {
  Q_OBJECT
 public:
  Relay(quint16 target) : target_(target) {
    moveToThread(&thread_);
    thread_.start();
    QMetaObject::invokeMethod(this, &Relay::open, Qt::BlockingQueuedConnection);
  }
  ~Relay() override {
    QMetaObject::invokeMethod(this, &Relay::shut, Qt::BlockingQueuedConnection);
    thread_.quit();
    thread_.wait();
  }
  quint16 port() const { return port_; }
  /// The server goes away: every connection cut, new ones refused.
  void away() { QMetaObject::invokeMethod(this, &Relay::shut, Qt::BlockingQueuedConnection); }
  /// The server is back, on the same port.
  void back() { QMetaObject::invokeMethod(this, &Relay::open, Qt::BlockingQueuedConnection); }

 private:
  void open() {
    if (!server_) {
      server_ = new QTcpServer(this);
      connect(server_, &QTcpServer::newConnection, this, &Relay::accept);
    }
    if (!server_->listen(QHostAddress::LocalHost, port_)) qWarning("relay: %s", qPrintable(server_->errorString()));
    port_ = server_->serverPort();
  }
  void shut() {
    if (server_) server_->close();
    for (QTcpSocket* s : findChildren<QTcpSocket*>()) {
      s->abort();
      s->deleteLater();
    }
  }
  void accept() {
    while (QTcpSocket* in = server_->nextPendingConnection()) {
      in->setParent(this);
      auto* out = new QTcpSocket(this);
      out->connectToHost(QHostAddress::LocalHost, target_);
      if (!out->waitForConnected(5000)) {
        in->abort();
        continue;
      }
      auto pipe = [](QTcpSocket* from, QTcpSocket* to) {
        connect(from, &QTcpSocket::readyRead, to, [from, to] { to->write(from->readAll()); });
        connect(from, &QTcpSocket::disconnected, to, [to] { to->disconnectFromHost(); });
      };
      pipe(in, out);
      pipe(out, in);
      if (in->bytesAvailable() > 0) out->write(in->readAll());
    }
  }
  QThread thread_;
  QTcpServer* server_ = nullptr;
  quint16 target_ = 0, port_ = 0;
};

const char* kScene = R"({
  "patient": {"phantom": "box", "size": [0.06, 0.06, 0.03], "resolution": 0.006},
  "tissue": {"young_modulus": 19000, "poisson_ratio": 0.45},
  "fingers": [{"radius": 0.008, "path": [[0, 0.0, 0.0, 0.039], [0.3, 0.004, 0.0, 0.034]]}],
  "duration": 0.3
})";

// A station's session recording: `ticks` ticks of one finger, closed.
void record_session(const std::string& path, int ticks) {
  const sim::Scenario s = sim::parse_scenario(kScene, "scene.json");
  RecordingWriter w(path, {{"scenario", nlohmann::json::parse(sim::scenario_to_json(s))}}, 1);
  for (int i = 0; i < ticks; ++i) {
    const Eigen::Vector3d x(0.001 * i, 0, 0.035), f(0, 0, 0.01 * i);
    w.add_tick(0.001 * (i + 1), &x, &f);
  }
  w.close();
}

ExamResult result(const std::string& trainee, const std::string& case_name, const std::string& recording, int k) {
  ExamResult r;
  r.trainee = trainee;
  r.case_name = case_name;
  r.started = "2026-11-24T09:" + std::string(k < 10 ? "0" : "") + std::to_string(k) + ":00Z";
  r.duration = 200 + k;
  r.coverage_light = 0.5;
  r.exam_time = 100 + k;
  r.score = {{"k", k}};
  r.recording = recording;
  return r;
}

std::string folder(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("palpation-tst-classroom-" + std::to_string(::getpid())) / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d.string();
}

// A server URL with its port replaced (through the relay).
std::string via_port(const std::string& url, quint16 port) {
  QUrl u(QString::fromStdString(url));
  u.setPort(port);
  return u.toString().toStdString();
}

}  // namespace

class TestClassroomLibrary : public QObject {
  Q_OBJECT
 private slots:
  void cleanupTestCase() {
    test_db::drop_all();
    std::error_code ec;
    fs::remove_all(fs::temp_directory_path() / ("palpation-tst-classroom-" + std::to_string(::getpid())), ec);
  }

  // Six stations at once on a new library: the first ones create it together (once), each
  // imports a patient, all try the same name (one gets it, the others are told it is
  // taken), each records sessions and stores their results for a trainee of its own and
  // for one trainee they all share (added by whichever comes first).
  void severalStationsAtOnce_data() { test_db::add_rows(); }
  void severalStationsAtOnce() {
    QFETCH(QString, backend);
    PALPATION_SKIP_WITHOUT_SERVER(backend);
    QTest::failOnWarning(QRegularExpression("."));  // no Qt SQL warnings on stderr either
    const std::string where = test_db::new_library(backend, "stations");
    QVERIFY2(!where.empty(), "no database made on the test server");
    const std::string recordings = folder("stations-" + backend.toStdString());
    constexpr int kStations = 6, kExams = 3;
    QMutex m;
    QStringList errors;
    int same_name_added = 0, same_name_taken = 0;
    std::vector<std::thread> stations;
    for (int k = 0; k < kStations; ++k)
      stations.emplace_back([&, k] {
        const std::string me = "station-" + std::to_string(k);
        try {
          PatientLibrary::Options o;
          o.db = where;
          o.busy_timeout_ms = 20000;
          o.pending_dir = recordings + "/pending-" + me;
          PatientLibrary lib(o);
          PatientRecord p;
          p.name = "scan-" + me;
          p.category = "imported";
          p.body = {{"patient", {{"mesh", p.name + ".pmesh"}}}};
          p.mesh = std::string("\0mesh\xff", 6) + me;
          lib.add(p);
          p.name = "same-name";
          try {
            lib.add(p);
            QMutexLocker l(&m);
            ++same_name_added;
          } catch (const LibraryError& e) {
            QMutexLocker l(&m);
            if (QString(e.what()).contains("patient \"same-name\" already exists")) ++same_name_taken;
            else errors << QString::fromStdString(me + ": " + e.what());
          }
          lib.add_trainee("trainee of " + me);
          for (int i = 0; i < kExams; ++i) {
            const std::string rec = recordings + "/" + me + "-" + std::to_string(i) + ".palrec";
            record_session(rec, 200 + 10 * k + i);
            const StoreOutcome own = lib.store_result(result("trainee of " + me, "paper-case", rec, i), false);
            const StoreOutcome shared = lib.store_result(result("the class", "breast-medium", rec, 10 * k + i));
            if (own.id <= 0 || shared.id <= 0) {
              QMutexLocker l(&m);
              errors << QString::fromStdString(me + ": not stored: " + own.message + shared.message);
            }
          }
        } catch (const std::exception& e) {
          QMutexLocker l(&m);
          errors << QString::fromStdString(me + ": " + e.what());
        }
      });
    for (auto& t : stations) t.join();
    QVERIFY2(errors.isEmpty(), qPrintable(errors.join("\n")));
    QCOMPARE(same_name_added, 1);
    QCOMPARE(same_name_taken, kStations - 1);

    PatientLibrary lib({where});
    QCOMPARE(QString::fromStdString(lib.opened_as()), QString("opened"));
    const auto all = lib.list();
    // The built-ins once each, every station's patient, the one "same-name".
    std::set<std::string> names;
    for (const auto& p : all) QVERIFY2(names.insert(p.name).second, p.name.c_str());
    QCOMPARE(all.size(), PatientLibrary::builtin_patients().size() + kStations + 1);
    for (int k = 0; k < kStations; ++k) {
      const std::string me = "station-" + std::to_string(k);
      const auto scan = lib.find("scan-" + me);
      QVERIFY(scan);
      QCOMPARE(scan->mesh, std::string("\0mesh\xff", 6) + me);
      const auto own = lib.results("trainee of " + me);
      QCOMPARE(own.size(), std::size_t(kExams));
      for (int i = 0; i < kExams; ++i) {
        QCOMPARE(own[std::size_t(i)].score["k"].get<int>(), i);
        // Each station's recording whole, as it wrote it.
        const Recording rec = read_recording(own[std::size_t(i)].recording);
        QVERIFY(rec.complete);
        QCOMPARE(rec.ticks(), std::size_t(200 + 10 * k + i));
      }
    }
    QCOMPARE(lib.trainees().size(), std::size_t(kStations + 1));
    const auto shared = lib.results("the class");
    QCOMPARE(shared.size(), std::size_t(kStations * kExams));
    std::set<int> ks;
    for (const auto& r : shared) ks.insert(r.score["k"].get<int>());
    QCOMPARE(ks.size(), shared.size());
  }

  // The server goes away mid-session and comes back.
  void serverGoesAwayAndComesBack() {
    PALPATION_SKIP_WITHOUT_SERVER(QString("postgresql"));
    QTest::failOnWarning(QRegularExpression("."));  // no Qt SQL warnings on stderr either
    const std::string direct = test_db::new_library("postgresql", "away");
    QVERIFY2(!direct.empty(), "no database made on the test server");
    Relay relay(quint16(QUrl(QString::fromStdString(direct)).port(5432)));
    QVERIFY(relay.port() > 0);
    const std::string where = via_port(direct, relay.port());
    const QString server = test_db::shown(where);
    const std::string dir = folder("away");
    PatientLibrary::Options o;
    o.db = where;
    o.pending_dir = dir + "/pending";
    o.connect_timeout_s = 5;
    auto lib = std::make_unique<PatientLibrary>(o);
    QVERIFY(lib->pending().empty());
    const std::size_t patients = lib->list().size();
    const std::string rec1 = dir + "/exam-1.palrec", rec2 = dir + "/exam-2.palrec", rec3 = dir + "/exam-3.palrec";
    record_session(rec1, 100);
    QVERIFY(lib->store_result(result("Al", "paper-case", rec1, 1)).id > 0);

    // Mid-session the server goes away; the exam ends and its result cannot be stored.
    record_session(rec2, 150);
    relay.away();
    const StoreOutcome kept = lib->store_result(result("Al", "breast-medium", rec2, 2));
    QCOMPARE(kept.id, std::int64_t(0));
    const QString msg = QString::fromStdString(kept.message);
    QVERIFY2(msg.startsWith(server + ": cannot reach the PostgreSQL server") && !msg.contains('\n') && msg.contains("kept on this station") &&
                 msg.contains(QString::fromStdString(kept.kept)) && msg.contains(QString::fromStdString(rec2)) &&
                 !msg.contains(QUrl(QString::fromStdString(where)).password()),
             qPrintable(msg));
    QVERIFY(fs::exists(kept.kept));
    QCOMPARE(lib->pending(), std::vector<std::string>{kept.kept});
    QVERIFY(read_recording(rec2).complete);  // the recording on the station, whole
    // Everything else says so too, naming the server; nothing is kept for a bad value.
    QString e;
    try {
      lib->list();
    } catch (const ServerUnavailable& x) {
      e = x.what();
    }
    QVERIFY2(e.startsWith(server + ": cannot reach the PostgreSQL server") && !e.contains('\n'), qPrintable(e));
    qInfo("server away: %s", qPrintable(msg));
    ExamResult bad = result("Al", "paper-case", rec2, 3);
    bad.coverage_deep = 2;
    QVERIFY_THROWS_EXCEPTION(LibraryError, lib->store_result(bad));
    QCOMPARE(lib->pending().size(), std::size_t(1));
    // A second exam while the server is still away: kept too, after the first.
    record_session(rec3, 120);
    const StoreOutcome kept2 = lib->store_result(result("Bea", "breast-small", rec3, 4));
    QCOMPARE(kept2.id, std::int64_t(0));
    QCOMPARE(lib->pending().size(), std::size_t(2));
    // A station opening the library meanwhile is told so.
    e.clear();
    try {
      PatientLibrary other(o);
    } catch (const ServerUnavailable& x) {
      e = x.what();
    }
    QVERIFY2(e.startsWith(server + ": cannot reach the PostgreSQL server"), qPrintable(e));

    // The server is back: the same library object works again, and the kept results go
    // first, in their order, each once (Bea is added, as she was at the station).
    relay.back();
    QCOMPARE(lib->list().size(), patients);
    record_session(dir + "/exam-5.palrec", 50);
    const StoreOutcome later = lib->store_result(result("Al", "breast-large", dir + "/exam-5.palrec", 5));
    QVERIFY2(later.id > 0, later.message.c_str());
    QVERIFY(lib->pending().empty());
    QVERIFY(!fs::exists(kept.kept) && !fs::exists(kept2.kept));
    const auto al = lib->results("Al");
    QCOMPARE(al.size(), std::size_t(3));
    QCOMPARE(QString::fromStdString(al[1].case_name), QString("breast-medium"));
    QCOMPARE(QString::fromStdString(al[1].recording), QString::fromStdString(rec2));
    QCOMPARE(al[1].score["k"].get<int>(), 2);
    QCOMPARE(lib->results("Bea").size(), std::size_t(1));
    QVERIFY(read_recording(al[1].recording).complete);

    // A server restart: the server ends the station's connection; the next use reconnects
    // without an error.
    QVERIFY(test_db::on_server(QString::fromStdString("SELECT pg_terminate_backend(pid) FROM pg_stat_activity WHERE datname = '" +
                                                      QUrl(QString::fromStdString(direct)).path().mid(1).toStdString() + "'")));
    QCOMPARE(lib->list().size(), patients);
    QCOMPARE(lib->results("Al").size(), std::size_t(3));

    // Kept results are also sent when a station opens the library, and a kept result sent
    // twice (a program that stopped before removing its file, or two sending at once) is
    // stored once.
    relay.away();
    const StoreOutcome kept3 = lib->store_result(result("Al", "tumour-1.0cm-mid-firm", rec1, 6));
    QVERIFY(!kept3.kept.empty());
    const std::string copy = kept3.kept + ".copy";
    fs::copy_file(kept3.kept, copy);
    lib.reset();
    relay.back();
    lib = std::make_unique<PatientLibrary>(o);
    QVERIFY(lib->pending().empty());
    QCOMPARE(lib->results("Al").size(), std::size_t(4));
    fs::rename(copy, kept3.kept);
    QCOMPARE(lib->send_pending(), 1);
    QCOMPARE(lib->results("Al").size(), std::size_t(4));
    QVERIFY(lib->pending().empty());
  }
};

QTEST_GUILESS_MAIN(TestClassroomLibrary)
#include "tst_classroom_library.moc"
