// Gmsh meshing of the breast phantom and import of volume mesh files. The only file of
// the project that includes gmsh.h (design.md section 2). Gmsh keeps global state, so
// every use holds one process-wide lock from gmsh::initialize to gmsh::finalize; files
// are read, and scans tetrahedralised, in a child process (self_child.h), because Gmsh's
// readers crash on some corrupt files and a mesher's hang must not hold the caller.
#include "mesh_gmsh.h"

#include <gmsh.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <unordered_map>
#include <utility>

#if defined(__unix__)
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "self_child.h"
#endif

namespace palpation::sim {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Serialises all use of Gmsh in this process (its state is global; gmsh::initialize
/// cannot be called twice at the same time).
std::mutex& gmsh_mutex() {
  static std::mutex m;
  return m;
}

/// One Gmsh API session: initialize on entry, finalize on every exit (also on
/// exceptions). The caller holds gmsh_mutex(), or is a child process that owns its copy
/// of Gmsh alone.
class GmshSession {
 public:
  explicit GmshSession(int threads) {
    // No argv, no gmshrc/gmsh-options files: the same result on every machine.
    gmsh::initialize(0, nullptr, /*readConfigFiles=*/false);
    gmsh::option::setNumber("General.Terminal", 0);      // no console output
    gmsh::option::setNumber("General.Verbosity", 2);     // errors and warnings reach the logger
    gmsh::option::setNumber("General.AbortOnError", 3);  // errors throw (the API default is 2)
    gmsh::option::setNumber("General.NumThreads", threads);
    gmsh::option::setNumber("Mesh.MaxNumThreads1D", threads);
    gmsh::option::setNumber("Mesh.MaxNumThreads2D", threads);
    gmsh::option::setNumber("Mesh.MaxNumThreads3D", threads);
    gmsh::logger::start();
  }
  ~GmshSession() {
    try {
      gmsh::logger::stop();
      gmsh::finalize();
    } catch (...) {
      // Nothing sensible to do while unwinding.
    }
  }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

  /// The last error Gmsh logged (empty when none), for messages.
  static std::string last_error() {
    std::string e;
    try {
      gmsh::logger::getLastError(e);
    } catch (...) {
    }
    // Without trailing line breaks.
    while (!e.empty() && (e.back() == '\n' || e.back() == ' ')) e.pop_back();
    return e;
  }
};

/// Text of an exception Gmsh threw: std::exception, a string, or anything else.
std::string reason_of(std::exception_ptr p) {
  std::string r;
  try {
    std::rethrow_exception(p);
  } catch (const std::exception& e) {
    r = e.what();
  } catch (const std::string& s) {
    r = s;
  } catch (const char* s) {
    r = s ? s : "";
  } catch (...) {
  }
  const std::string last = GmshSession::last_error();
  if (r.empty() || r == "std::exception") r = last;
  if (r.empty()) r = "unknown Gmsh error";
  // One printable line: readers quote bytes of a garbage file in their messages.
  for (char& ch : r)
    if (static_cast<unsigned char>(ch) < 0x20 || static_cast<unsigned char>(ch) > 0x7e) ch = '?';
  if (r.size() > 200) r = r.substr(0, 200) + "...";
  return r;
}

/// Linear tetrahedra of the current model's volume entities, with the nodes they use
/// renumbered 0..n-1 in order of first use. `region_of` maps a volume entity tag to the
/// region tag of its elements; entities it maps to a negative value are skipped.
/// Quadratic tetrahedra (type 11) contribute their four corner nodes.
template <class RegionOf>
TetMesh extract_tets(RegionOf region_of) {
  TetMesh mesh;
  gmsh::vectorpair vols;
  gmsh::model::getEntities(vols, 3);
  std::unordered_map<std::size_t, int> index;  // Gmsh node tag -> compact index
  std::vector<std::size_t> used;               // compact index -> Gmsh node tag
  for (const auto& [dim, tag] : vols) {
    const int region = region_of(tag);
    if (region < 0) continue;
    for (const int type : {4, 11}) {
      std::vector<std::size_t> elems, enodes;
      gmsh::model::mesh::getElementsByType(type, elems, enodes, tag);
      const std::size_t per = type == 4 ? 4 : 10;
      if (elems.empty() || enodes.size() != elems.size() * per) continue;
      for (std::size_t e = 0; e < elems.size(); ++e) {
        std::array<int, 4> t{};
        for (int k = 0; k < 4; ++k) {
          const std::size_t gt = enodes[e * per + static_cast<std::size_t>(k)];
          auto [it, fresh] = index.try_emplace(gt, static_cast<int>(used.size()));
          if (fresh) used.push_back(gt);
          t[static_cast<std::size_t>(k)] = it->second;
        }
        mesh.tets.push_back(t);
        mesh.region.push_back(region);
      }
    }
  }
  if (mesh.tets.empty()) return mesh;

  // Coordinates of the used nodes only.
  mesh.nodes.assign(used.size(), Eigen::Vector3d::Zero());
  std::vector<std::size_t> tags;
  std::vector<double> coord, param;
  gmsh::model::mesh::getNodes(tags, coord, param, -1, -1, /*includeBoundary=*/true,
                              /*returnParametricCoord=*/false);
  std::vector<char> seen(used.size(), 0);
  for (std::size_t i = 0; i < tags.size(); ++i) {
    auto it = index.find(tags[i]);
    if (it == index.end()) continue;
    mesh.nodes[static_cast<std::size_t>(it->second)] =
        Eigen::Vector3d(coord[3 * i], coord[3 * i + 1], coord[3 * i + 2]);
    seen[static_cast<std::size_t>(it->second)] = 1;
  }
  for (std::size_t i = 0; i < seen.size(); ++i)
    if (!seen[i])
      throw std::runtime_error("tetrahedra refer to node " + std::to_string(used[i]) + ", which has no coordinates");
  return mesh;
}

/// Normalised ellipsoidal radius of an inclusion, sqrt(sum ((x - c)/r)^2), as a Gmsh
/// MathEval expression: 1 on its surface, 2 one radius outside it.
std::string normalized_radius_expr(const Inclusion& inc) {
  std::ostringstream f;
  f.precision(17);
  f << "Sqrt(";
  const char* axis[3] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k) {
    if (k) f << " + ";
    f << "((" << axis[k] << " - (" << inc.center[k] << ")) / " << inc.radii[k] << ")^2";
  }
  f << ")";
  return f.str();
}

/// Refuses files Gmsh would not read with a mesh reader. Gmsh runs any file it does not
/// recognise, and a .msh file without a mesh header, through its .geo script
/// interpreter, which can execute shell commands (System) and end the process (Exit);
/// it also hands .gz files to the shell and some extensions to solvers. Only
/// extensions with a dedicated mesh reader pass, and .msh only with a mesh header (the
/// same test Gmsh's MergeFile makes before calling its MSH reader).
void check_mesh_file(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot be read");
  if (ext == ".msh") {
    char header[16] = {};
    in.read(header, sizeof(header));
    const std::string head(header, static_cast<std::size_t>(in.gcount()));
    for (const char* magic : {"$MeshFormat", "$NOD", "$ELM", "$Comments"})
      if (head.rfind(magic, 0) == 0) return;
    throw std::runtime_error(path + ": not a Gmsh mesh file (no $MeshFormat header)");
  }
  for (const char* ok : {".vtk", ".mesh", ".unv", ".bdf", ".nas"})
    if (ext == ok) return;
  throw std::runtime_error(path + ": unsupported mesh format \"" + ext +
                           "\" (volume meshes: .msh, .vtk, .mesh, .unv, .bdf, .nas, .pmesh)");
}

/// Reads `path` with Gmsh in this process (caller holds the lock or is the child).
/// On failure leaves `mesh` empty and sets `error` to the reason.
void read_here(const std::string& path, TetMesh& mesh, std::string& error) {
  try {
    GmshSession session(1);
    gmsh::model::add("import");
    gmsh::merge(path);
    gmsh::vectorpair vols;
    gmsh::model::getEntities(vols, 3);
    std::unordered_map<int, int> order;  // volume entity tag -> 0-based index
    for (std::size_t i = 0; i < vols.size(); ++i) order[vols[i].second] = static_cast<int>(i);
    mesh = extract_tets([&order](int tag) {
      auto it = order.find(tag);
      return it == order.end() ? -1 : it->second;
    });
  } catch (...) {
    mesh = TetMesh{};
    error = reason_of(std::current_exception());
  }
}

#if defined(__unix__)
/// Pipe message from the child: u8 ok; ok: u64 nnode, u64 ntet, f64[3 nnode], i32[4 ntet],
/// i32[ntet]; not ok: the error text.
std::string encode(const TetMesh& m, const std::string& error) {
  std::string b;
  auto put = [&b](const void* d, std::size_t n) { b.append(static_cast<const char*>(d), n); };
  const char ok = error.empty() ? 1 : 0;
  put(&ok, 1);
  if (!ok) {
    b += error;
    return b;
  }
  const std::uint64_t nn = m.nodes.size(), nt = m.tets.size();
  put(&nn, 8);
  put(&nt, 8);
  for (const auto& p : m.nodes) put(p.data(), 3 * sizeof(double));
  put(m.tets.data(), nt * 4 * sizeof(int));
  put(m.region.data(), nt * sizeof(int));
  return b;
}

bool decode(const std::string& b, TetMesh& m, std::string& error) {
  if (b.empty()) return false;
  if (b[0] != 1) {
    error = b.substr(1);
    if (error.empty()) error = "unknown Gmsh error";
    return true;
  }
  std::uint64_t nn = 0, nt = 0;
  if (b.size() < 17) return false;
  std::memcpy(&nn, b.data() + 1, 8);
  std::memcpy(&nt, b.data() + 9, 8);
  if (nn > (1ull << 31) || nt > (1ull << 31) ||
      b.size() != 17 + nn * 3 * sizeof(double) + nt * 5 * sizeof(int))
    return false;
  m.nodes.resize(nn);
  m.tets.resize(nt);
  m.region.resize(nt);
  const char* p = b.data() + 17;
  for (auto& v : m.nodes) {
    std::memcpy(v.data(), p, 3 * sizeof(double));
    p += 3 * sizeof(double);
  }
  if (nt > 0) {  // memcpy from/to an empty vector's null data() is undefined (UBSan)
    std::memcpy(m.tets.data(), p, nt * 4 * sizeof(int));
    p += nt * 4 * sizeof(int);
    std::memcpy(m.region.data(), p, nt * sizeof(int));
  }
  return true;
}

/// The mesher's input (the child's stdin): f64 edge, u64 nvert, u64 ntri, f64[3 nvert],
/// i32[3 ntri].
std::string encode_surface(const std::vector<Eigen::Vector3d>& v, const std::vector<std::array<int, 3>>& tris, double edge) {
  std::string b;
  const std::uint64_t nv = v.size(), nt = tris.size();
  b.append(reinterpret_cast<const char*>(&edge), 8);
  b.append(reinterpret_cast<const char*>(&nv), 8);
  b.append(reinterpret_cast<const char*>(&nt), 8);
  for (const auto& p : v) b.append(reinterpret_cast<const char*>(p.data()), 3 * sizeof(double));
  for (const auto& t : tris) b.append(reinterpret_cast<const char*>(t.data()), 3 * sizeof(int));
  return b;
}

bool decode_surface(const std::string& b, std::vector<Eigen::Vector3d>& v, std::vector<std::array<int, 3>>& tris, double& edge) {
  if (b.size() < 24) return false;
  std::uint64_t nv = 0, nt = 0;
  std::memcpy(&edge, b.data(), 8);
  std::memcpy(&nv, b.data() + 8, 8);
  std::memcpy(&nt, b.data() + 16, 8);
  const std::uint64_t rest = b.size() - 24;
  if (nv > rest / (3 * sizeof(double)) || nt > rest / (3 * sizeof(int)) || nv * 3 * sizeof(double) + nt * 3 * sizeof(int) != rest)
    return false;
  v.resize(nv);
  tris.resize(nt);
  const char* p = b.data() + 24;
  for (auto& x : v) {
    std::memcpy(x.data(), p, 3 * sizeof(double));
    p += 3 * sizeof(double);
  }
  for (auto& t : tris) {
    std::memcpy(t.data(), p, 3 * sizeof(int));
    p += 3 * sizeof(int);
  }
  return true;
}

/// The argv[1] that turns an executable into a Gmsh child (self_child.h).
constexpr const char* kChildFlag = "--palpation-internal-gmsh";

/// Runs a Gmsh job ("mesh" with `input`, or "read" with a path) in a re-executed child
/// (self_child.h: not fork(), whose child can hang on a lock another thread held).
/// Returns false only when no child could be started (the caller then runs the job in
/// process); otherwise fills `mesh` or `error`. `cancelled` (may be empty) is polled:
/// true kills the child.
bool run_in_child(const char* what, std::vector<std::string> args, std::string input, double timeout_s,
                  const std::function<bool()>& cancelled, TetMesh& mesh, std::string& error) {
  self_child::Job job;
  job.argv = {std::string("palpation-gmsh-") + what, kChildFlag};
  job.argv.insert(job.argv.end(), args.begin(), args.end());
  job.input = std::move(input);
  job.wall_seconds = timeout_s;
  job.cancelled = cancelled;
  self_child::Outcome o;
  try {
    o = self_child::run(job);
  } catch (const std::runtime_error&) {
    return false;
  }
  if (o.cancelled) {
    error = std::string("cancelled (the Gmsh ") + what + " was stopped)";
    return true;
  }
  if (o.timed_out) {
    std::ostringstream m;
    m << "the Gmsh " << what << " did not finish within " << static_cast<int>(timeout_s) << " s (stopped)";
    error = m.str();
    return true;
  }
  if (WIFSIGNALED(o.status)) {
    error = std::string("the Gmsh ") + what + " crashed (" + self_child::signal_name(WTERMSIG(o.status)) +
            "): the input is corrupt or not supported";
    return true;
  }
  if (!decode(o.output, mesh, error)) {
    mesh = TetMesh{};
    error = std::string("the Gmsh ") + what + " stopped without a result (corrupt input?)";
  }
  return true;
}
#endif

/// Tetrahedralises a closed surface (caller holds the lock or is the child): the surface
/// as a discrete entity, classified into patches (40 degree feature angle), reparametrised
/// and remeshed at `edge`, one volume inside.
void tetrahedralize_here(const std::vector<Eigen::Vector3d>& v, const std::vector<std::array<int, 3>>& tris, double edge,
                         TetMesh& mesh, std::string& error) {
  try {
    GmshSession session(1);
    gmsh::model::add("scan");
    const int surf = gmsh::model::addDiscreteEntity(2);
    std::vector<std::size_t> ntags(v.size());
    std::vector<double> coords;
    coords.reserve(3 * v.size());
    for (std::size_t i = 0; i < v.size(); ++i) {
      ntags[i] = i + 1;
      coords.insert(coords.end(), {v[i].x(), v[i].y(), v[i].z()});
    }
    gmsh::model::mesh::addNodes(2, surf, ntags, coords);
    std::vector<std::size_t> etags(tris.size()), enodes;
    enodes.reserve(3 * tris.size());
    for (std::size_t i = 0; i < tris.size(); ++i) {
      etags[i] = i + 1;
      for (int k = 0; k < 3; ++k) enodes.push_back(std::size_t(tris[i][std::size_t(k)]) + 1);
    }
    gmsh::model::mesh::addElementsByType(surf, 2, etags, enodes);
    gmsh::model::mesh::classifySurfaces(40.0 * kPi / 180.0, /*boundary=*/true, /*forReparametrization=*/true,
                                        /*curveAngle=*/kPi);
    gmsh::model::mesh::createGeometry();
    gmsh::vectorpair surfaces;
    gmsh::model::getEntities(surfaces, 2);
    std::vector<int> stags;
    for (const auto& [dim, tag] : surfaces) stags.push_back(tag);
    const int loop = gmsh::model::geo::addSurfaceLoop(stags);
    gmsh::model::geo::addVolume({loop});
    gmsh::model::geo::synchronize();
    gmsh::option::setNumber("Mesh.MeshSizeMax", edge);
    gmsh::option::setNumber("Mesh.MeshSizeMin", 0.0);
    gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
    gmsh::option::setNumber("Mesh.Optimize", 1);
    gmsh::option::setNumber("Mesh.ElementOrder", 1);
    gmsh::option::setNumber("Mesh.Algorithm3D", 1);
    gmsh::model::mesh::generate(3);
    mesh = extract_tets([](int) { return 0; });
    if (mesh.tets.empty()) error = "Gmsh produced no tetrahedra (is the surface closed?)";
  } catch (...) {
    mesh = TetMesh{};
    error = reason_of(std::current_exception());
  }
}

#if defined(__unix__)
/// The child: argv = {name, kChildFlag, "mesh"} (the surface on stdin) or {name,
/// kChildFlag, "read", path}. Writes encode()'s message to stdout; returns the exit status.
int child_main(int argc, char** argv) {
  const rlimit no_core{0, 0};
  setrlimit(RLIMIT_CORE, &no_core);  // a reader crash ends quietly
  TetMesh m;
  std::string why;
  if (argc == 3 && std::strcmp(argv[2], "mesh") == 0) {
    std::string in;
    std::vector<Eigen::Vector3d> v;
    std::vector<std::array<int, 3>> tris;
    double edge = 0;
    if (!self_child::read_all(STDIN_FILENO, in) || !decode_surface(in, v, tris, edge)) return 3;
    tetrahedralize_here(v, tris, edge, m, why);
  } else if (argc == 4 && std::strcmp(argv[2], "read") == 0) {
    read_here(argv[3], m, why);
  } else {
    return 3;
  }
  const std::string b = encode(m, why);
  return self_child::write_all(STDOUT_FILENO, b.data(), b.size()) ? 0 : 5;
}

// glibc passes (argc, argv, envp) to ELF constructors. This runs before main() of any
// executable that links the Gmsh jobs: started as their child, the process does the job
// and ends here (_exit: no static destructors, no atexit handlers, no leak checks).
__attribute__((constructor)) void gmsh_child_hook(int argc, char** argv, char**) {
  if (argc >= 2 && argv && argv[1] && std::strcmp(argv[1], kChildFlag) == 0) _exit(child_main(argc, argv));
}
#endif

}  // namespace

bool gmsh_available() { return true; }

TetMesh gmsh_breast(const BreastShape& shape, double edge, const std::vector<Inclusion>& inclusions,
                    const LogFn& log) {
  if (!(edge > 0) || !std::isfinite(edge)) throw std::runtime_error("edge length must be positive");
  if (!(shape.base_radius > 0) || !(shape.height > 0)) throw std::runtime_error("breast shape must have positive size");
  const double a = shape.base_radius, h = shape.height, cx = shape.center_x;  // m
  // Unrefined HXT meshes of the dome have about 4.2 V / edge^3 tetrahedra (measured);
  // beyond ~10 million Gmsh needs several GB and many minutes: refuse up front.
  double expected_tets = 4.2 * (2.0 / 3.0 * kPi * a * a * h) / (edge * edge * edge);
  // A refined skin adds its layer (3 mm at skin_edge; the dome's area is at most 2 pi a max(a, h)).
  if (shape.skin_edge > 0 && shape.skin_edge < edge)
    expected_tets += 4.2 * (2.0 * kPi * a * std::max(a, h) * 0.003) / (shape.skin_edge * shape.skin_edge * shape.skin_edge);
  if (expected_tets > 1e7) {
    std::ostringstream o;
    o.precision(3);
    o << "edge " << edge << " m would give about " << expected_tets / 1e6
      << " million tetrahedra (limit 10 million): use a larger edge length";
    throw std::runtime_error(o.str());
  }
  const auto t0 = std::chrono::steady_clock::now();

  std::lock_guard<std::mutex> lock(gmsh_mutex());
  GmshSession session(1);
  TetMesh mesh;
  int algorithm = 1;
  try {
    gmsh::model::add("breast");
    namespace occ = gmsh::model::occ;

    // Dome: upper half ball (polar angle 0..pi/2, flat disc on z = 0) of radius a about
    // (cx, 0, 0), stretched along z by h / a into the half ellipsoid.
    const int dome = occ::addSphere(cx, 0, 0, a, -1, 0.0, kPi / 2);
    occ::dilate({{3, dome}}, cx, 0, 0, 1.0, 1.0, h / a);

    // Inclusions whose bounding box reaches into the dome's bounding box. Spheres stay
    // exact spheres; ellipsoids are spheres of radius rx stretched along y and z.
    std::vector<int> inc_index;  // tool entity k -> inclusion index
    gmsh::vectorpair tools;
    for (std::size_t i = 0; i < inclusions.size(); ++i) {
      const Inclusion& inc = inclusions[i];
      const Eigen::Vector3d& c = inc.center;
      const Eigen::Vector3d& r = inc.radii;
      if (!c.allFinite() || !r.allFinite() || (r.array() <= 0).any()) continue;
      if (c.z() + r.z() <= 0 || c.z() - r.z() >= h || c.x() + r.x() <= cx - a || c.x() - r.x() >= cx + a ||
          c.y() + r.y() <= -a || c.y() - r.y() >= a)
        continue;
      const int s = occ::addSphere(c.x(), c.y(), c.z(), r.x());
      if (r.y() != r.x() || r.z() != r.x()) occ::dilate({{3, s}}, c.x(), c.y(), c.z(), 1.0, r.y() / r.x(), r.z() / r.x());
      tools.push_back({3, s});
      inc_index.push_back(static_cast<int>(i));
    }

    // Volume tag -> region. Fragmenting makes the inclusion surfaces interior faces of
    // one conforming mesh; pieces of inclusions outside the dome are removed.
    std::unordered_map<int, int> region_of;
    std::vector<char> embedded(tools.size(), 0);  // tool k has a piece inside the dome
    if (tools.empty()) {
      occ::synchronize();
      region_of[dome] = 0;
    } else {
      gmsh::vectorpair out;
      std::vector<gmsh::vectorpair> map;
      occ::fragment({{3, dome}}, tools, out, map);
      if (map.size() != 1 + tools.size()) throw std::runtime_error("OpenCASCADE fragment returned an unexpected map");
      for (const auto& [dim, tag] : map[0])
        if (dim == 3) region_of[tag] = 0;
      // The first inclusion that contains a piece names it (as apply_inclusions does).
      for (std::size_t k = tools.size(); k-- > 0;)
        for (const auto& [dim, tag] : map[k + 1])
          if (dim == 3 && region_of.count(tag)) {
            region_of[tag] = inc_index[k] + 1;
            embedded[k] = 1;
          }
      gmsh::vectorpair outside;
      for (const auto& [dim, tag] : out)
        if (dim == 3 && !region_of.count(tag)) outside.push_back({dim, tag});
      if (!outside.empty()) occ::remove(outside, /*recursive=*/true);
      occ::synchronize();
    }
    if (region_of.empty()) throw std::runtime_error("the dome vanished in the boolean operations");

    // Mesh size: `edge` everywhere, refined to 0.6 edge inside each inclusion and up to
    // one radius around it (normalised radius s <= 2), graded back to `edge` by s = 3.
    // Small inclusions get at least two elements across their smallest radius.
    gmsh::option::setNumber("Mesh.MeshSizeMax", edge);
    gmsh::option::setNumber("Mesh.MeshSizeMin", 0.0);
    gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
    gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
    gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
    std::vector<double> thresholds;
    for (std::size_t k = 0; k < tools.size(); ++k) {
      if (!embedded[k]) continue;
      const Inclusion& inc = inclusions[static_cast<std::size_t>(inc_index[k])];
      const double fine = std::max(std::min(0.6 * edge, 0.5 * inc.radii.minCoeff()), 0.05 * edge);
      const int f = gmsh::model::mesh::field::add("MathEval");
      gmsh::model::mesh::field::setString(f, "F", normalized_radius_expr(inc));
      const int t = gmsh::model::mesh::field::add("Threshold");
      gmsh::model::mesh::field::setNumber(t, "IField", f);
      gmsh::model::mesh::field::setNumber(t, "LcMin", fine);
      gmsh::model::mesh::field::setNumber(t, "LcMax", edge);
      gmsh::model::mesh::field::setNumber(t, "DistMin", 2.0);
      gmsh::model::mesh::field::setNumber(t, "DistMax", 3.0);
      thresholds.push_back(t);
    }
    // The skin: `skin_edge` down to 3 mm below it, graded back to `edge` by 1 cm. Depth
    // below the skin is taken as (1 - rho) min(a, h), rho the dome's normalized radius:
    // exact on the axis, up to a / h deeper elsewhere (the refined layer is then thicker
    // by that ratio at the rim, never thinner).
    if (shape.skin_edge > 0 && shape.skin_edge < edge) {
      std::ostringstream f;
      f.precision(17);
      f << "(1 - Sqrt(((x - (" << cx << ")) / " << a << ")^2 + (y / " << a << ")^2 + (z / " << h << ")^2)) * "
        << std::min(a, h);
      const int d = gmsh::model::mesh::field::add("MathEval");
      gmsh::model::mesh::field::setString(d, "F", f.str());
      const int t = gmsh::model::mesh::field::add("Threshold");
      gmsh::model::mesh::field::setNumber(t, "IField", d);
      gmsh::model::mesh::field::setNumber(t, "LcMin", shape.skin_edge);
      gmsh::model::mesh::field::setNumber(t, "LcMax", edge);
      gmsh::model::mesh::field::setNumber(t, "DistMin", 0.003);
      gmsh::model::mesh::field::setNumber(t, "DistMax", 0.01);
      thresholds.push_back(t);
    }
    if (!thresholds.empty()) {
      const int m = gmsh::model::mesh::field::add("Min");
      gmsh::model::mesh::field::setNumbers(m, "FieldsList", thresholds);
      gmsh::model::mesh::field::setAsBackgroundMesh(m);
    }

    gmsh::option::setNumber("Mesh.Optimize", 1);
    gmsh::option::setNumber("Mesh.ElementOrder", 1);
    gmsh::model::mesh::generate(2);
    // The classic Delaunay mesher first, HXT only if it fails. HXT's result depends on
    // memory addresses (three runs of the same breast gave three meshes; with address
    // randomisation off, one), so every machine and every clone meshed another patient and
    // tests with mesh-dependent figures drifted. Delaunay gave the same mesh in every run;
    // it is about 1.6-2x slower to mesh (paper 1.9 -> 3.0 s, fine 3.9 -> 7.7 s on the 2-core
    // VM) and, at the same edge length, has about 12% more nodes.
    try {
      gmsh::option::setNumber("Mesh.Algorithm3D", 1);
      gmsh::model::mesh::generate(3);
    } catch (...) {
      algorithm = 10;
      gmsh::model::mesh::clear();
      gmsh::option::setNumber("Mesh.Algorithm3D", 10);
      gmsh::model::mesh::generate(3);
    }

    mesh = extract_tets([&region_of](int tag) {
      auto it = region_of.find(tag);
      return it == region_of.end() ? -1 : it->second;
    });
  } catch (...) {
    throw std::runtime_error("Gmsh: " + reason_of(std::current_exception()));
  }
  if (mesh.tets.empty()) throw std::runtime_error("Gmsh produced no tetrahedra");

  // The chest wall is exactly z = 0 (fix_base selects z <= zmin + 1e-6).
  for (auto& p : mesh.nodes)
    if (std::abs(p.z()) < 1e-9) p.z() = 0.0;
  mesh.orient();

  if (log) {
    const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::ostringstream o;
    o.precision(3);
    o << "gmsh: breast edge " << edge * 1000 << " mm";
    if (shape.skin_edge > 0) o << " (skin " << shape.skin_edge * 1000 << " mm)";
    o << ", " << inclusions.size() << " inclusion(s): "
      << mesh.num_nodes() << " nodes, " << mesh.num_tets() << " tetrahedra in " << sec << " s ("
      << (algorithm == 10 ? "HXT" : "Delaunay") << ")";
    log(o.str());
  }
  return mesh;
}

TetMesh gmsh_tetrahedralize(const std::vector<Eigen::Vector3d>& vertices, const std::vector<std::array<int, 3>>& triangles,
                            double edge, double timeout_s, const std::function<bool()>& cancelled) {
  if (!(edge > 0) || !std::isfinite(edge)) throw std::runtime_error("edge length must be positive");
  if (triangles.size() < 4) throw std::runtime_error("the surface has fewer than 4 triangles");
  TetMesh mesh;
  std::string error;
#if defined(__unix__)
  if (!run_in_child("mesher", {"mesh"}, encode_surface(vertices, triangles, edge), timeout_s, cancelled, mesh, error))
#endif
  {
    std::lock_guard<std::mutex> lock(gmsh_mutex());
    tetrahedralize_here(vertices, triangles, edge, mesh, error);
  }
  if (!error.empty()) throw std::runtime_error("Gmsh: " + error);
  mesh.orient();
  return mesh;
}

TetMesh gmsh_read_volume(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) throw std::runtime_error(path + ": no such file");
  if (!fs::is_regular_file(path, ec)) throw std::runtime_error(path + ": not a regular file");
  check_mesh_file(path);

  TetMesh mesh;
  std::string error;
#if defined(__unix__)
  // Gmsh's readers trust the file (a corrupt node tag in a .msh file is a segfault), so
  // they run in a child process that sends the mesh back through a socket; a crash or a
  // hang there costs an error message, not the process.
  const double size_mb = static_cast<double>(fs::file_size(path, ec)) / 1e6;
  const double timeout_s = 60.0 + 5.0 * size_mb;  // generous: readers do ~50 MB/s
  if (!run_in_child("reader", {"read", path}, {}, timeout_s, {}, mesh, error))
#endif
  {
    std::lock_guard<std::mutex> lock(gmsh_mutex());
    read_here(path, mesh, error);
  }
  if (!error.empty()) throw std::runtime_error(path + ": " + error);
  if (mesh.tets.empty()) throw std::runtime_error(path + ": contains no tetrahedra");
  mesh.orient();
  return mesh;
}

}  // namespace palpation::sim
