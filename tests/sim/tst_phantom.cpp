// Breast phantom meshing (sim/mesh_gmsh.cpp), mesh import, and the binary model cache
// (sim/model_cache.cpp). Checks geometric invariants of the generated mesh rather than
// stored counts: Gmsh's parallel HXT mesher is not bit-reproducible across runs.
#include <QtTest>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <unistd.h>

#include "mesh.h"
#include "mesh_gmsh.h"
#include "model_cache.h"
#include "phantom.h"
#include "scenario.h"

using namespace palpation::sim;
using V3 = Eigen::Vector3d;

namespace {

constexpr double kPi = 3.14159265358979323846;

// The paper's tumour (scenario_builtin.cpp, paper_sweep): sphere of 15 mm radius, 3 cm
// above the chest wall, 1 cm off the breast axis.
Inclusion paper_tumour() {
  Inclusion inc;
  inc.shape = "sphere";
  inc.center = V3(0.125, 0.0, 0.03);
  inc.radii = V3::Constant(0.015);
  return inc;
}

// Normalised ellipsoidal radius of a point w.r.t. the dome: 1 on the skin.
double dome_radius(const BreastShape& b, const V3& p) {
  const double dx = (p.x() - b.center_x) / b.base_radius, dy = p.y() / b.base_radius, dz = p.z() / b.height;
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

double volume_of(const TetMesh& m, int region = -1) {
  double v = 0;
  for (int e = 0; e < m.num_tets(); ++e) {
    if (region >= 0 && m.region[e] != region) continue;
    const auto& t = m.tets[e];
    v += tet_volume(m.nodes[t[0]], m.nodes[t[1]], m.nodes[t[2]], m.nodes[t[3]]);
  }
  return v;
}

V3 centroid(const TetMesh& m, int e) {
  const auto& t = m.tets[e];
  return 0.25 * (m.nodes[t[0]] + m.nodes[t[1]] + m.nodes[t[2]] + m.nodes[t[3]]);
}

double mean_edge(const TetMesh& m, int e) {
  const auto& t = m.tets[e];
  double s = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) s += (m.nodes[t[i]] - m.nodes[t[j]]).norm();
  return s / 6;
}

std::string write_file(const QString& dir, const std::string& name, const std::string& bytes) {
  const std::string path = (std::filesystem::path(dir.toStdString()) / name).string();
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

// The mesh as a Gmsh MSH 2.2 ASCII file: elementary tag region + 1 per tetrahedron.
std::string to_msh22(const TetMesh& m) {
  std::string s = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n" + std::to_string(m.num_nodes()) + "\n";
  char line[160];
  for (int i = 0; i < m.num_nodes(); ++i) {
    std::snprintf(line, sizeof(line), "%d %.17g %.17g %.17g\n", i + 1, m.nodes[i].x(), m.nodes[i].y(), m.nodes[i].z());
    s += line;
  }
  s += "$EndNodes\n$Elements\n" + std::to_string(m.num_tets()) + "\n";
  for (int e = 0; e < m.num_tets(); ++e) {
    const auto& t = m.tets[e];
    std::snprintf(line, sizeof(line), "%d 4 2 %d %d %d %d %d %d\n", e + 1, m.region[e] + 1, m.region[e] + 1, t[0] + 1,
                  t[1] + 1, t[2] + 1, t[3] + 1);
    s += line;
  }
  return s + "$EndElements\n";
}

// Expects gmsh_read_volume(path) to throw a one-line message that names the file.
#define EXPECT_READ_FAILS(path_expr)                                                  \
  do {                                                                                \
    const std::string p_ = (path_expr);                                               \
    bool threw_ = false;                                                              \
    try {                                                                             \
      gmsh_read_volume(p_);                                                           \
    } catch (const std::runtime_error& e_) {                                          \
      threw_ = true;                                                                  \
      const std::string what_ = e_.what();                                            \
      QVERIFY2(what_.rfind(p_ + ": ", 0) == 0, what_.c_str());                        \
      QVERIFY2(what_.find('\n') == std::string::npos, what_.c_str());                 \
    }                                                                                 \
    QVERIFY2(threw_, ("no error for " + p_).c_str());                                 \
  } while (0)


// A 10 cm cube's closed, outward-oriented surface (12 triangles).
std::vector<Eigen::Vector3d> cube_vertices() {
  std::vector<Eigen::Vector3d> v;
  for (int i = 0; i < 8; ++i) v.emplace_back(i & 1 ? 0.1 : 0.0, i & 2 ? 0.1 : 0.0, i & 4 ? 0.1 : 0.0);
  return v;
}
std::vector<std::array<int, 3>> cube_triangles() {
  return {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
          {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
}

}  // namespace

class TestPhantom : public QObject {
  Q_OBJECT

  BreastShape shape_;
  double edge_ = 0;  // m, "coarse"
  TetMesh coarse_;   // with the paper's tumour
  std::vector<std::string> log_;

 private slots:
  void initTestCase() {
    QVERIFY(gmsh_available());
    edge_ = *resolution_edge("breast", "coarse");
    coarse_ = gmsh_breast(shape_, edge_, {paper_tumour()}, [this](const std::string& l) { log_.push_back(l); });
  }

  void coarseMeshIsValid() {
    QVERIFY(coarse_.num_nodes() > 0);
    QVERIFY(coarse_.num_tets() > 0);
    QCOMPARE(coarse_.region.size(), coarse_.tets.size());
    QCOMPARE(QString::fromStdString(coarse_.validate()), QString());
    for (int e = 0; e < coarse_.num_tets(); ++e) {
      const auto& t = coarse_.tets[e];
      QVERIFY(tet_volume(coarse_.nodes[t[0]], coarse_.nodes[t[1]], coarse_.nodes[t[2]], coarse_.nodes[t[3]]) > 0);
    }
    // Every node is used by a tetrahedron (compact numbering).
    std::vector<char> used(coarse_.nodes.size(), 0);
    for (const auto& t : coarse_.tets)
      for (int k : t) used[k] = 1;
    QVERIFY(std::all_of(used.begin(), used.end(), [](char u) { return u; }));
    // One log line with the counts.
    QCOMPARE(log_.size(), std::size_t(1));
    QVERIFY(log_[0].find(std::to_string(coarse_.num_nodes()) + " nodes") != std::string::npos);
  }

  // Nodes lie in the dome. Surface nodes are placed on the CAD surface (the dilated
  // sphere is an exact rational surface, OpenCASCADE tolerance 1e-7 m), so the true
  // deviation is ~1e-7 m; the contract tolerance is 0.5 edge (a misplaced or stray node
  // would be off by at least an element), and the tight bound is checked as well.
  void nodesInsideDome() {
    double worst = 0;  // m, outside distance (normal-radius excess times the larger semi-axis)
    for (const auto& p : coarse_.nodes) {
      QVERIFY(p.z() >= 0);
      worst = std::max(worst, (dome_radius(shape_, p) - 1) * shape_.base_radius);
    }
    QVERIFY2(worst < 0.5 * edge_, std::to_string(worst).c_str());
    QVERIFY2(worst < 1e-5, std::to_string(worst).c_str());
  }

  // The chest wall: base nodes exactly at z = 0, covering the base disc.
  void baseNodesAtZeroExist() {
    int base = 0;
    double rmax = 0;
    for (const auto& p : coarse_.nodes) {
      if (p.z() != 0.0) continue;
      ++base;
      rmax = std::max(rmax, std::hypot(p.x() - shape_.center_x, p.y()));
    }
    // Base disc area / node spacing^2 ~ pi 0.08^2 / 0.0119^2 ~ 140 nodes: ask for a third.
    QVERIFY2(base > 50, std::to_string(base).c_str());
    QVERIFY(rmax > 0.99 * shape_.base_radius);
    // Nothing hovers just above the base (fix_base selects z <= 1e-6).
    for (const auto& p : coarse_.nodes) QVERIFY(p.z() == 0.0 || p.z() > 1e-6);
  }

  // Volume against 2/3 pi a^2 h. The dome is convex and its surface nodes lie on it, so
  // the mesh is an inscribed polyhedron: its volume is below the exact one, short by
  // about area x mean sagitta of the flat triangles. A triangle of edge l on a surface
  // of curvature radius R sags at most l^2/(6R), on average about l^2/(12R); with
  // l = 11.9 mm, R >= h^2/a = 53 mm and a skin area ~0.037 m^2 the deficit is
  // <= 0.037 x 2.2e-4 m = 8.2e-6 m^3, 0.9 % of 8.7e-4 m^3. 3 % leaves room for the
  // coarser triangles Gmsh places on the base rim.
  void volumeMatchesHalfEllipsoid() {
    const double exact = 2.0 / 3.0 * kPi * shape_.base_radius * shape_.base_radius * shape_.height;
    const double v = volume_of(coarse_);
    QVERIFY2(std::abs(v - exact) < 0.03 * exact, (std::to_string(v) + " vs " + std::to_string(exact)).c_str());
    QVERIFY(v < exact * (1 + 1e-6));  // inscribed
  }

  // The tumour: conforming region 1, refined, volume ~ 4/3 pi r^3. At 0.6 edge = 6.9 mm
  // on r = 15 mm the inscribed sphere misses about area x l^2/(12 r) = 2.8e-3 m^2 x
  // 2.6e-4 m, 5 % (measured 7.6 %: the surface triangles come out a little larger than
  // the target size); 10 % is the contract.
  void inclusionRegionConformsToSphere() {
    const Inclusion inc = paper_tumour();
    const double r = inc.radii.x();
    const double exact = 4.0 / 3.0 * kPi * r * r * r;
    std::set<int> regions(coarse_.region.begin(), coarse_.region.end());
    QCOMPARE(regions, (std::set<int>{0, 1}));
    const double v = volume_of(coarse_, 1);
    QVERIFY2(std::abs(v - exact) < 0.10 * exact, (std::to_string(v) + " vs " + std::to_string(exact)).c_str());
    QVERIFY(v < exact * (1 + 1e-6));  // inscribed in a convex body

    // Region 1 lies inside the sphere; region 0 outside it, up to the chord sagitta
    // (< 0.6 edge^2 / (6 r) ~ 0.04 r): apply_inclusions' centroid test agrees.
    for (int e = 0; e < coarse_.num_tets(); ++e) {
      const double d = (centroid(coarse_, e) - inc.center).norm();
      if (coarse_.region[e] == 1)
        QVERIFY(d < r);
      else
        QVERIFY(d > 0.9 * r);
    }
    // Faces between the regions have their nodes on the sphere (the surface is
    // embedded, not approximated by element faces that happen to be near it).
    static const int kFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
    std::map<std::array<int, 3>, int> face_region;
    int interface_faces = 0;
    for (int e = 0; e < coarse_.num_tets(); ++e) {
      for (const auto& f : kFace) {
        std::array<int, 3> k{coarse_.tets[e][f[0]], coarse_.tets[e][f[1]], coarse_.tets[e][f[2]]};
        std::sort(k.begin(), k.end());
        auto [it, fresh] = face_region.try_emplace(k, coarse_.region[e]);
        if (fresh || it->second == coarse_.region[e]) continue;
        ++interface_faces;
        for (int n : k) QVERIFY(std::abs((coarse_.nodes[n] - inc.center).norm() - r) < 1e-6);
      }
    }
    QVERIFY(interface_faces > 20);

    // Refinement: elements inside the tumour are smaller than far from it.
    double in = 0, far = 0;
    int nin = 0, nfar = 0;
    for (int e = 0; e < coarse_.num_tets(); ++e) {
      const double d = (centroid(coarse_, e) - inc.center).norm();
      if (coarse_.region[e] == 1) {
        in += mean_edge(coarse_, e);
        ++nin;
      } else if (d > 4 * r) {
        far += mean_edge(coarse_, e);
        ++nfar;
      }
    }
    QVERIFY(nin > 0 && nfar > 0);
    QVERIFY2(in / nin < 0.8 * far / nfar, (std::to_string(in / nin) + " vs " + std::to_string(far / nfar)).c_str());
  }

  // An inclusion entirely outside is ignored; one sticking out of the skin is clipped
  // to the dome; tags follow the inclusion index (i + 1) whatever is skipped.
  void clippedAndOutsideInclusions() {
    Inclusion outside = paper_tumour();
    outside.center = V3(0.5, 0.0, 0.03);
    Inclusion top;
    top.shape = "ellipsoid";
    top.center = V3(shape_.center_x, 0.0, shape_.height);  // on the nipple
    top.radii = V3(0.010, 0.012, 0.008);
    const TetMesh m = gmsh_breast(shape_, edge_, {outside, top}, {});
    QCOMPARE(QString::fromStdString(m.validate()), QString());
    std::set<int> regions(m.region.begin(), m.region.end());
    QCOMPARE(regions, (std::set<int>{0, 2}));
    for (const auto& p : m.nodes) QVERIFY(dome_radius(shape_, p) < 1 + 1e-5);
    // Roughly the lower half of the ellipsoid (the skin is flatter than the ellipsoid).
    const double half = 2.0 / 3.0 * kPi * top.radii.prod();
    const double v = volume_of(m, 2);
    QVERIFY2(v > 0.6 * half && v < 1.1 * half, (std::to_string(v) + " vs " + std::to_string(half)).c_str());
  }

  void noInclusionsIsAllBulk() {
    const TetMesh m = gmsh_breast(shape_, 0.02, {}, {});
    QCOMPARE(QString::fromStdString(m.validate()), QString());
    for (int r : m.region) QCOMPARE(r, 0);
  }

  // A refined skin: the elements touching the skin shrink toward skin_edge, those deep
  // inside stay at the edge. Measured on the coarse breast (11.9 mm) with a 4 mm skin:
  // see the qInfo line.
  void skinRefinementShrinksTheSkinElements() {
    auto mean_edges = [](const TetMesh& m, double& skin, double& deep, int& skin_count) {
      const BreastShape b;
      double s = 0, d = 0;
      int ns = 0, nd = 0;
      for (const auto& t : m.tets) {
        Eigen::Vector3d c = Eigen::Vector3d::Zero();
        double len = 0;
        bool on_skin = false;  // a node on the upper skin (CAD surface, 1e-7 m)
        for (int i = 0; i < 4; ++i) {
          const Eigen::Vector3d& p = m.nodes[t[i]];
          c += p / 4.0;
          on_skin = on_skin || (p.z() > 0.03 && std::fabs(b.surface_z(p.x(), p.y()) - p.z()) < 1e-5);
          for (int j = i + 1; j < 4; ++j) len += (m.nodes[t[i]] - m.nodes[t[j]]).norm() / 6.0;
        }
        const double depth = b.surface_z(c.x(), c.y()) - c.z();  // vertical, below the skin
        if (on_skin) { s += len; ++ns; }
        if (depth > 0.025 && c.z() > 0.01) { d += len; ++nd; }   // deep inside
      }
      skin = s / std::max(ns, 1);
      deep = d / std::max(nd, 1);
      skin_count = ns;
    };
    BreastShape refined = shape_;
    refined.skin_edge = 0.004;
    const TetMesh m = gmsh_breast(refined, edge_, {}, {});
    const TetMesh plain = gmsh_breast(shape_, edge_, {}, {});
    QCOMPARE(QString::fromStdString(m.validate()), QString());
    double skin = 0, deep = 0, skin0 = 0, deep0 = 0;
    int n = 0, n0 = 0;
    mean_edges(m, skin, deep, n);
    mean_edges(plain, skin0, deep0, n0);
    qInfo("skin 4 mm: %d nodes (plain %d); mean edge at the skin %.2f mm (plain %.2f), deep %.2f mm (plain %.2f)",
          m.num_nodes(), plain.num_nodes(), skin * 1e3, skin0 * 1e3, deep * 1e3, deep0 * 1e3);
    QVERIFY(m.num_nodes() > 3 * plain.num_nodes());
    QVERIFY2(skin < 0.6 * skin0, "the skin's elements shrink");
    // Gmsh's elements come out longer than asked (3.3-3.5 across where 4 were asked in
    // the tumours, sim/convergence.h): within 1.6 times.
    QVERIFY2(skin < 1.6 * refined.skin_edge, "to about skin_edge");
    QVERIFY2(std::fabs(deep - deep0) < 0.25 * deep0, "the deep elements stay");
  }

  void badArgumentsThrow() {
    QVERIFY_THROWS_EXCEPTION(std::runtime_error, gmsh_breast(shape_, 0.0, {}, {}));
    QVERIFY_THROWS_EXCEPTION(std::runtime_error, gmsh_breast(shape_, std::nan(""), {}, {}));
  }

  // design.md section 5: "paper" has about 9,100 nodes and 44,000 tetrahedra with the
  // paper's tumour embedded. HXT varies by a few tenths of a percent between runs.
  void paperResolutionMatchesPaper() {
    const TetMesh m = gmsh_breast(shape_, *resolution_edge("breast", "paper"), {paper_tumour()}, {});
    QVERIFY2(std::abs(m.num_nodes() - 9100) < 0.10 * 9100, std::to_string(m.num_nodes()).c_str());
    QVERIFY2(std::abs(m.num_tets() - 44000) < 0.10 * 44000, std::to_string(m.num_tets()).c_str());
  }

  // Written as MSH 2.2 and read back: same tetrahedra (up to numbering), same regions.
  void readVolumeRoundTrip() {
    QTemporaryDir dir;
    const std::string path = write_file(dir.path(), "breast.msh", to_msh22(coarse_));
    const TetMesh m = gmsh_read_volume(path);
    QCOMPARE(m.num_nodes(), coarse_.num_nodes());
    QCOMPARE(m.num_tets(), coarse_.num_tets());
    QCOMPARE(QString::fromStdString(m.validate()), QString());
    for (int r = 0; r <= 1; ++r)
      QVERIFY(std::abs(volume_of(m, r) - volume_of(coarse_, r)) < 1e-12 * volume_of(coarse_));
    // Same tetrahedra: compare sorted centroids (coordinates survive %.17g exactly).
    auto centroids = [](const TetMesh& t) {
      std::vector<std::array<double, 4>> c;
      for (int e = 0; e < t.num_tets(); ++e) {
        const V3 p = centroid(t, e);
        c.push_back({p.x(), p.y(), p.z(), double(t.region[e])});
      }
      std::sort(c.begin(), c.end());
      return c;
    };
    QVERIFY(centroids(m) == centroids(coarse_));
  }

  void readGarbageThrowsNamingTheFile() {
    QTemporaryDir dir;
    std::mt19937 rng(42);
    std::string noise(4000, '\0');
    for (char& c : noise) c = static_cast<char>(rng());
    EXPECT_READ_FAILS(write_file(dir.path(), "noise.msh", noise));
    EXPECT_READ_FAILS(write_file(dir.path(), "noise.vtk", noise));
    EXPECT_READ_FAILS(write_file(dir.path(), "noise.mesh", noise));
    EXPECT_READ_FAILS(write_file(dir.path(), "header.msh", "$MeshFormat\n" + noise));
    EXPECT_READ_FAILS(write_file(dir.path(), "empty.msh", ""));
    EXPECT_READ_FAILS(write_file(dir.path(), "notes.txt", "hello\n"));
    EXPECT_READ_FAILS(write_file(dir.path(), "surface.stl", "solid s\nendsolid s\n"));
    EXPECT_READ_FAILS((std::filesystem::path(dir.path().toStdString()) / "missing.msh").string());
    EXPECT_READ_FAILS(dir.path().toStdString());  // a folder
    // A mesh without tetrahedra (one triangle).
    EXPECT_READ_FAILS(write_file(dir.path(), "tri.msh",
                                 "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n"
                                 "$EndNodes\n$Elements\n1\n1 2 2 1 1 1 2 3\n$EndElements\n"));
  }

  // Gmsh runs unrecognised files through its .geo interpreter, which can execute shell
  // commands and exit the process: such files must never reach it.
  void scriptsAreNeverExecuted() {
    QTemporaryDir dir;
    const std::string marker = (std::filesystem::path(dir.path().toStdString()) / "executed").string();
    const std::string script = "System \"touch " + marker + "\";\nExit;\n";
    EXPECT_READ_FAILS(write_file(dir.path(), "script.msh", script));
    EXPECT_READ_FAILS(write_file(dir.path(), "script.geo", script));
    EXPECT_READ_FAILS(write_file(dir.path(), "script.dat", script));
    QVERIFY(!std::filesystem::exists(marker));
  }

  // A corrupt node tag makes Gmsh 4.8's MSH4 reader segfault; the reader runs in a child
  // process, so this is an error message, not a crash.
  void readerCrashIsContained() {
    QTemporaryDir dir;
    const std::string head =
        "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Entities\n0 0 0 1\n1 0 0 0 1 1 1 0 0\n$EndEntities\n"
        "$Nodes\n1 4 1 4\n3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n$EndNodes\n"
        "$Elements\n1 1 1 1\n3 1 4 1\n";
    const TetMesh one = gmsh_read_volume(write_file(dir.path(), "one.msh", head + "1 1 2 3 4\n$EndElements\n"));
    QCOMPARE(one.num_tets(), 1);
    QCOMPARE(one.num_nodes(), 4);
    QVERIFY(tet_volume(one.nodes[one.tets[0][0]], one.nodes[one.tets[0][1]], one.nodes[one.tets[0][2]],
                       one.nodes[one.tets[0][3]]) > 0);
    EXPECT_READ_FAILS(write_file(dir.path(), "crash.msh", head + "1 1 2 3 1999999999992\n$EndElements\n"));
  }

  // Gmsh's jobs run in a freshly executed copy of this program (sim/self_child.h), not a
  // fork() of it: the child seen under /proc has the job's own argv and this executable.
  // A forked child would show this test's argv.
  void gmshJobsRunInAFreshProcess() {
    auto cmdline = [](const std::filesystem::path& proc) {
      std::vector<std::string> args;
      std::ifstream cl(proc / "cmdline", std::ios::binary);
      std::string arg;
      while (std::getline(cl, arg, '\0')) args.push_back(arg);
      return args;
    };
    const std::vector<std::string> own = cmdline("/proc/self");
    const auto self = std::filesystem::read_symlink("/proc/self/exe");
    std::vector<std::string> seen;
    std::string exe, error;
    TetMesh m;
    // The child lives for the mesher's run only: on a loaded machine the polling below can
    // miss it, so a few jobs are tried. A child caught between its spawn and its exec
    // still shows this test's argv: it is polled again until it shows its own.
    for (int attempt = 0; attempt < 5 && seen.empty(); ++attempt) {
      std::atomic<bool> done{false};
      std::thread job([&] {
        try {
          m = gmsh_tetrahedralize(cube_vertices(), cube_triangles(), 0.006, 120.0, {});
        } catch (const std::exception& e) {
          error = e.what();
        }
        done = true;
      });
      while (!done && seen.empty()) {
        for (const auto& d : std::filesystem::directory_iterator("/proc")) {
          std::ifstream st(d.path() / "stat");
          std::string pid, comm, state;
          long ppid = 0;
          if (!(st >> pid >> comm >> state >> ppid) || ppid != long(::getpid())) continue;
          const std::vector<std::string> args = cmdline(d.path());
          if (args.empty() || args == own) continue;
          std::error_code ec;
          exe = std::filesystem::read_symlink(d.path() / "exe", ec).string();
          seen = args;
          break;
        }
        std::this_thread::sleep_for(std::chrono::microseconds(200));
      }
      job.join();
      QVERIFY2(error.empty(), error.c_str());
      qInfo("attempt %d: child %s", attempt + 1, seen.empty() ? "not seen" : "seen");
    }
    QVERIFY(m.num_tets() > 100);
    QVERIFY2(seen.size() >= 3, "the mesher's child process was not seen");
    QCOMPARE(QString::fromStdString(seen[0]), QStringLiteral("palpation-gmsh-mesher"));
    QCOMPARE(QString::fromStdString(seen[1]), QStringLiteral("--palpation-internal-gmsh"));
    QCOMPARE(QString::fromStdString(seen[2]), QStringLiteral("mesh"));
    QCOMPARE(QString::fromStdString(exe), QString::fromStdString(self.string()));
  }

  // The reason for the above: with three threads allocating, forked children of an
  // AddressSanitizer build hung on the allocator's lock (2 of 120 jobs, each until its
  // deadline; CI's sanitizer stage lost tst_review that way). Every job must finish.
  void gmshJobsFinishWhileOtherThreadsAllocate() {
    std::atomic<bool> stop{false};
    std::vector<std::thread> churn;
    for (int k = 0; k < 3; ++k)
      churn.emplace_back([&stop, k] {
        std::vector<std::unique_ptr<char[]>> keep(64);
        unsigned s = 1u + unsigned(k);
        while (!stop) {
          s = s * 1103515245u + 12345u;
          keep[s % 64].reset(new char[16 + (s >> 8) % 5000]);
        }
      });
    QStringList failed;
    const int jobs = 12;
    for (int i = 0; i < jobs; ++i) {
      try {
        const TetMesh m = gmsh_tetrahedralize(cube_vertices(), cube_triangles(), 0.03, 30.0, {});
        if (m.num_tets() < 6) failed << QStringLiteral("%1: %2 tetrahedra").arg(i).arg(m.num_tets());
      } catch (const std::exception& e) {
        failed << QStringLiteral("%1: %2").arg(i).arg(QString::fromStdString(e.what()));
      }
    }
    stop = true;
    for (auto& t : churn) t.join();
    QVERIFY2(failed.isEmpty(), qPrintable(failed.join(QStringLiteral("; "))));
  }

  // --- model cache ---------------------------------------------------------------

  void cacheRoundTrip() {
    QTemporaryDir dir;
    const std::string path = (std::filesystem::path(dir.path().toStdString()) / "m.pmesh").string();
    save_mesh_cache(path, coarse_, "key-1");
    TetMesh m;
    std::string why;
    QVERIFY2(load_mesh_cache(path, "key-1", m, &why), why.c_str());
    QCOMPARE(m.num_nodes(), coarse_.num_nodes());
    QVERIFY(m.nodes == coarse_.nodes);
    QVERIFY(m.tets == coarse_.tets);
    QVERIFY(m.region == coarse_.region);
    QCOMPARE(m.hash(), coarse_.hash());
    // No temporary files left behind.
    int files = 0;
    for ([[maybe_unused]] const auto& f : std::filesystem::directory_iterator(dir.path().toStdString())) ++files;
    QCOMPARE(files, 1);
  }

  void cacheRejectsFlippedByte() {
    QTemporaryDir dir;
    const std::string path = (std::filesystem::path(dir.path().toStdString()) / "m.pmesh").string();
    save_mesh_cache(path, coarse_, "k");
    std::string bytes;
    {
      std::ifstream in(path, std::ios::binary);
      bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    bytes[40 + 8 * 3 * 100 + 3] ^= 0x10;  // inside node 100's coordinates
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
    TetMesh m;
    std::string why;
    QVERIFY(!load_mesh_cache(path, "k", m, &why));
    QCOMPARE(QString::fromStdString(why), QString("corrupt: checksum mismatch"));
    QCOMPARE(m.num_nodes(), 0);  // untouched on failure
  }

  void cacheRejectsOtherKey() {
    QTemporaryDir dir;
    const std::string path = (std::filesystem::path(dir.path().toStdString()) / "m.pmesh").string();
    save_mesh_cache(path, coarse_, "breast edge=0.0115");
    TetMesh m;
    std::string why;
    QVERIFY(!load_mesh_cache(path, "breast edge=0.005", m, &why));
    QVERIFY2(why.rfind("stale", 0) == 0, why.c_str());
    // Without the key check (a mesh file on its own) it loads.
    QVERIFY(load_mesh_cache(path, "", m, &why, /*check_key=*/false));
    QCOMPARE(m.num_tets(), coarse_.num_tets());
  }

  void cacheRejectsTruncatedAndMissing() {
    QTemporaryDir dir;
    const std::string path = (std::filesystem::path(dir.path().toStdString()) / "m.pmesh").string();
    save_mesh_cache(path, coarse_, "k");
    const std::uintmax_t size = std::filesystem::file_size(path);
    TetMesh m;
    std::string why;
    for (const std::uintmax_t keep : {size - 1, size / 2, std::uintmax_t{20}, std::uintmax_t{0}}) {
      std::filesystem::resize_file(path, keep);
      QVERIFY(!load_mesh_cache(path, "k", m, &why));
      QVERIFY2(why.rfind("corrupt", 0) == 0, why.c_str());
    }
    QVERIFY(!load_mesh_cache(path + ".nope", "k", m, &why));
    QCOMPARE(QString::fromStdString(why), QString("missing"));
  }
};

QTEST_APPLESS_MAIN(TestPhantom)
#include "tst_phantom.moc"
