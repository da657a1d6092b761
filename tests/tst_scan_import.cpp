// Scan import: good meshes (STL, OBJ, PLY; a dome tipped on its side: the base plane is
// found) become tetrahedral meshes with the base on z = 0; broken ones (open,
// non-manifold, empty, garbage bytes) are refused saying exactly what is wrong;
// the import can be cancelled.
#include <QtTest>

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "mesh_gmsh.h"
#include "scan_import.h"
#include "scenario.h"
#include "simulation.h"

using namespace palpation;
using namespace palpation::app;
namespace fs = std::filesystem;

namespace {

std::string tmp(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("palpation-tst-scan-" + std::to_string(::getpid()));
  fs::create_directories(d);
  return (d / name).string();
}

std::string data(const std::string& name) { return std::string(PALPATION_TEST_DATA) + "/" + name; }

QString import_error(const std::string& path, ImportOptions opt = {}) {
  opt.edge = 0.012;
  try {
    import_scan(path, opt);
  } catch (const ImportError& e) {
    return QString::fromStdString(e.what());
  }
  return {};
}

}  // namespace

class TestScanImport : public QObject {
  Q_OBJECT
 private slots:
  void initTestCase() {
    if (!scan_reader_available()) QSKIP("this build has no assimp");
  }

  void goodMeshes_data() {
    QTest::addColumn<QString>("file");
    QTest::newRow("stl") << QString("dome.stl");
    QTest::newRow("obj") << QString("dome.obj");
    QTest::newRow("ply") << QString("dome.ply");
    QTest::newRow("stl on its side") << QString("dome-side.stl");
  }
  void goodMeshes() {
    QFETCH(QString, file);
    const std::string path = data(file.toStdString());
    // The surface alone: closed, manifold, the base found.
    SurfaceMesh s = read_surface(path);
    const SurfaceReport rep = repair_surface(s);
    QVERIFY2(rep.ok(), rep.problems().c_str());
    QCOMPARE(rep.open_edges, 0);
    if (file.endsWith(".stl")) QVERIFY(rep.merged_vertices > 0 || s.vertices.size() == 98);  // STL repeats corners
    const BasePlane b = find_base_plane(s);
    const Eigen::Vector3d want = file.contains("side") ? Eigen::Vector3d(0, 1, 0) : Eigen::Vector3d(0, 0, -1);
    QVERIFY2(b.normal.dot(want) > 0.999, qPrintable(QString("normal %1 %2 %3").arg(b.normal.x()).arg(b.normal.y()).arg(b.normal.z())));
    QVERIFY(std::abs(b.area - 3.14159 * 0.05 * 0.05) < 0.1 * 3.14159 * 0.05 * 0.05);  // the 16-gon base disc
    if (!sim::gmsh_available()) QSKIP("no Gmsh: tetrahedralisation not tested");
    ImportOptions opt;
    opt.edge = 0.012;
    int calls = 0;
    opt.progress = [&](double, const std::string&) {
      ++calls;
      return true;
    };
    const ImportResult r = import_scan(path, opt);
    QVERIFY(r.mesh.num_tets() > 50);
    QVERIFY(r.mesh.validate().empty());
    QVERIFY(calls >= 4);
    Eigen::Vector3d lo, hi;
    r.mesh.bounds(lo, hi);
    QCOMPARE(lo.z(), 0.0);
    QVERIFY(std::abs(hi.z() - 0.04) < 2e-3);
    double vol = 0;
    for (const auto& t : r.mesh.tets)
      vol += sim::tet_volume(r.mesh.nodes[t[0]], r.mesh.nodes[t[1]], r.mesh.nodes[t[2]], r.mesh.nodes[t[3]]);
    const double exact = 2.0 / 3.0 * 3.14159265 * 0.05 * 0.05 * 0.04;
    QVERIFY2(std::abs(vol - exact) < 0.08 * exact, qPrintable(QString::number(vol / exact)));
    qInfo("%s: %d nodes, %d tetrahedra in %.2f s (meshing %.2f s)", qPrintable(file), r.mesh.num_nodes(), r.mesh.num_tets(),
          r.seconds, r.mesh_seconds);
  }

  void brokenMeshesSayWhatIsWrong_data() {
    QTest::addColumn<QString>("file");
    QTest::addColumn<QString>("expected");
    QTest::newRow("open") << QString("open-dome.stl") << QString("16 open edges (holes: the surface is not closed)");
    QTest::newRow("non-manifold") << QString("nonmanifold-dome.obj") << QString("1 non-manifold edge");
    QTest::newRow("empty") << QString("empty.stl") << QString("empty file (0 bytes)");
    QTest::newRow("garbage stl") << QString("garbage.stl") << QString("not a mesh file assimp reads");
    QTest::newRow("garbage ply") << QString("garbage.ply") << QString("not a PLY file");
    QTest::newRow("no triangles") << QString("no-faces.obj") << QString("empty: no triangles");
  }
  void brokenMeshesSayWhatIsWrong() {
    QFETCH(QString, file);
    QFETCH(QString, expected);
    const std::string path = data(file.toStdString());
    const QString e = import_error(path);
    QVERIFY2(e.startsWith(QString::fromStdString(path) + ": ") && e.contains(expected), qPrintable(e));
  }

  void wrongUnitsAndBasePlaneOverride() {
    const std::string mm = tmp("dome-mm.obj");
    write_test_dome(mm, 50, 40);  // millimetres
    QVERIFY(import_error(mm).contains("--scale"));
    if (!sim::gmsh_available()) QSKIP("no Gmsh");
    ImportOptions opt;
    opt.edge = 0.012;
    opt.scale = 0.001;
    BasePlane b;
    b.normal = Eigen::Vector3d(0, 0, -1);
    b.offset = 0;
    b.automatic = false;
    opt.base = b;
    const ImportResult r = import_scan(mm, opt);
    QVERIFY(!r.base.automatic);
    QVERIFY(r.mesh.num_tets() > 50);
    // A plane through the middle of the dome is refused (the body reaches beyond it).
    b.offset = -0.02;
    opt.base = b;
    const QString e = import_error(mm, opt);
    QVERIFY2(e.contains("base plane"), qPrintable(e));
  }

  void importedMeshSimulates() {
    if (!sim::gmsh_available()) QSKIP("no Gmsh");
    ImportOptions opt;
    opt.edge = 0.012;
    const ImportResult r = import_scan(data("dome.stl"), opt);
    sim::Scenario s = sim::parse_scenario(
        R"({"patient": {"phantom": "box"}, "fingers": [{"path": [[0, 0, 0, 0.05], [0.05, 0, 0, 0.046]]}], "duration": 0.05})", "x");
    sim::Model m = sim::build_scenario_model(s, r.mesh);
    QVERIFY(m.num_free() < m.num_nodes());  // the base is fixed
    QVERIFY(m.num_free() > 0);
  }

  void cancellation() {
    if (!sim::gmsh_available()) QSKIP("no Gmsh");
    ImportOptions opt;
    opt.edge = 0.012;
    opt.progress = [](double f, const std::string&) { return f < 0.25; };  // cancel before meshing
    QVERIFY_EXCEPTION_THROWN(import_scan(data("dome.obj"), opt), std::runtime_error);
    // Cancelled while Gmsh runs (a fine mesh): the child is stopped.
    opt.edge = 0.0015;
    opt.progress = [](double f, const std::string&) { return f <= 0.3; };
    QString e;
    try {
      import_scan(data("dome.obj"), opt);
    } catch (const std::runtime_error& ex) {
      e = ex.what();
    }
    QCOMPARE(e, QString("cancelled"));
  }
};

QTEST_APPLESS_MAIN(TestScanImport)
#include "tst_scan_import.moc"
