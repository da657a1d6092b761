// CUDA backends: "cuda" (fast), and the library baselines "cuda-csr" (textbook port) and
// "cuda-bsr" (good first port) of baseline.cuh. backend_cpu.cpp is the
// specification; this file composes the stages of sim/cuda/ into the same step on the GPU
// (docs/gpu-notes.md has the design, the alternatives measured and the numbers), and
// detects the device.
//
// Per step, in one stream (three launches and one synchronisation when in motion):
//   k_element   (element.cu) per element: F, rotation (warm-started quaternion), r_a = R g_a
//               and the element's right-hand-side matrix Q (elastic force and K v folded
//               in), one compact record per element; extra blocks do the contact detection
//               at start-of-step positions against the end-of-step fingers (contact.cuh).
//   k_assemble  (assembly.cu) one thread per 3x3 block, summing over the element pairs
//               listed for it when the backend is made (the diagonal's thread also inverts
//               it for block-Jacobi), and one per block row for its right-hand side (no
//               atomics, every output written once).
//   k_pcg       (pcg.cu) one persistent cooperative kernel: the PCG of solve_cg.h (warm
//               start, restart and stopping rules), two grid barriers per iteration (the
//               search direction is formed inside the SpMV), rows held in registers when
//               they fit; then v += dv, x += h v, the rest rule, and the finger outputs at
//               the end state.
//   With the nodal-pressure element (tissue.element) k_assemble also forms the free
//   nodes' couplings of its volumetric term, up to three small kernels between k_assemble
//   and k_pcg form the rest of it, and k_pcg applies it in each product (pressure.cuh).
//   The kernels write the small result (finger sums, statistics) into mapped pinned memory:
//   no copy is queued; the host synchronises once.
// At rest with no contact only k_detect (contact.cu) runs (GPU detection, the result read
// the same way). The baselines share k_element and k_assemble and replace k_pcg by their
// cuSPARSE/cuBLAS loop (baseline.cu), then k_detect (finish).
// The knobs for measurements (environment) are read once per backend: tuning.h.
#include "backend_cuda.h"
#include "multigrid_keeper.h"
#include "nodal_pressure.h"

#include <cuda_runtime.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "cuda/assembly.cuh"
#include "cuda/baseline.cuh"
#include "cuda/common.cuh"
#include "cuda/contact.cuh"
#include "cuda/device_info.h"
#include "cuda/element.cuh"
#include "cuda/multigrid.cuh"
#include "cuda/pcg.cuh"
#include "cuda/pressure.cuh"
#include "cuda/tuning.h"

namespace palpation::sim {

namespace cuda {

const DeviceInfo& device_info() {
  static DeviceInfo info;
  static std::once_flag once;
  std::call_once(once, [] {
    int count = 0;
    const cudaError_t e = cudaGetDeviceCount(&count);
    if (e != cudaSuccess) {
      info.why = std::string("no usable CUDA device (") + cudaGetErrorName(e) + ": " + cudaGetErrorString(e) + ")";
      cudaGetLastError();
      return;
    }
    if (count <= 0) {
      info.why = "no CUDA device found";
      return;
    }
    cudaDeviceProp prop{};
    if (cudaGetDeviceProperties(&prop, 0) != cudaSuccess) {
      info.why = "cudaGetDeviceProperties failed";
      cudaGetLastError();
      return;
    }
    info.name = prop.name;
    info.sms = prop.multiProcessorCount;
    info.cc_major = prop.major;
    info.cc_minor = prop.minor;
    info.cooperative = prop.cooperativeLaunch != 0;
    if (prop.major < 6) {
      info.why = std::string("GPU ") + prop.name + " has compute capability " + std::to_string(prop.major) + "." +
                 std::to_string(prop.minor) + " (6.0 or newer needed)";
      return;
    }
    if (!info.cooperative) {
      info.why = std::string("GPU ") + prop.name + " does not support cooperative launches";
      return;
    }
    const cudaError_t e2 = cudaFree(nullptr);  // creates the context: catches driver/runtime mismatch
    if (e2 != cudaSuccess) {
      info.why = std::string("cannot use the CUDA device (") + cudaGetErrorName(e2) + ": " + cudaGetErrorString(e2) + ")";
      cudaGetLastError();
      return;
    }
    info.ok = true;
  });
  return info;
}

namespace {

/// Host copies of the model arrays in the GPU layout (built once per backend).
template <class T>
struct HostLayout {
  std::vector<int4> tets;
  std::vector<T> grad, vol;
  std::vector<int> block_row, pair_ptr, pairs, free_surf;
  std::vector<T> mass;

  explicit HostLayout(const Model& m) {
    const int ne = m.num_tets(), nf = m.num_free(), nb = m.num_blocks();
    tets.resize(ne);
    grad.resize(12 * std::size_t(ne));
    vol.resize(ne);
    for (int e = 0; e < ne; ++e) {
      tets[e] = make_int4(m.tets[e][0], m.tets[e][1], m.tets[e][2], m.tets[e][3]);
      for (int a = 0; a < 4; ++a)
        for (int c = 0; c < 3; ++c) grad[12 * std::size_t(e) + 3 * a + c] = T(m.grad[e][a][c]);
      vol[e] = T(m.volume[e]);
    }
    block_row.resize(nb);
    for (int i = 0; i < nf; ++i)
      for (int k = m.row_ptr[i]; k < m.row_ptr[i + 1]; ++k) block_row[k] = i;
    // The element pairs of each block (AssembleArgs::pairs), by ascending element.
    pair_ptr.assign(nb + 1, 0);
    for (int e = 0; e < ne; ++e)
      for (int ab = 0; ab < 16; ++ab)
        if (const int k = m.tet_block[e][ab]; k >= 0) ++pair_ptr[k + 1];
    for (int k = 0; k < nb; ++k) pair_ptr[k + 1] += pair_ptr[k];
    pairs.resize(pair_ptr[nb]);
    {
      std::vector<int> fill(pair_ptr.begin(), pair_ptr.end() - 1);
      for (int e = 0; e < ne; ++e)
        for (int ab = 0; ab < 16; ++ab)
          if (const int k = m.tet_block[e][ab]; k >= 0) pairs[fill[k]++] = (e << 4) | ab;  // ab = a << 2 | b
    }
    const int ns = static_cast<int>(m.surface_nodes.size());
    free_surf.assign(nf, -1);
    for (int s = 0; s < ns; ++s) {
      const int i = m.dof[m.surface_nodes[s]];
      if (i >= 0) free_surf[i] = s;
    }
    mass.resize(m.num_nodes());
    for (int j = 0; j < m.num_nodes(); ++j) mass[j] = T(m.mass[j]);
  }
};

enum class Solver { Persistent, Csr, Bsr };

/// Stage timing with events (CudaTuning::profile): printed when the backend dies. Beside
/// the stages, the host's time from one solved step's end (its result read) to the next
/// one's first launch: what the caller (Simulation, the bench) spends between steps.
struct Profiler {
  bool on = false;
  static constexpr int kStages = 4;
  const char* names[kStages] = {"element+detect", "assemble", "solve+finish", "wait"};
  cudaEvent_t ev[kStages + 1]{};
  std::vector<float> ms[kStages];
  std::vector<float> between;  // ms, host
  std::chrono::steady_clock::time_point left{};
  int steps = 0;
  void init(bool enable) {
    on = enable;
    if (on)
      for (auto& e : ev) CU(cudaEventCreate(&e));
  }
  void mark(int i, cudaStream_t s) {
    if (!on) return;
    if (i == 0 && left != std::chrono::steady_clock::time_point{})
      between.push_back(std::chrono::duration<float, std::milli>(std::chrono::steady_clock::now() - left).count());
    CU(cudaEventRecord(ev[i], s));
  }
  void collect() {
    if (!on) return;
    for (int i = 0; i < kStages; ++i) {
      float t = 0;
      CU(cudaEventElapsedTime(&t, ev[i], ev[i + 1]));
      ms[i].push_back(t);
    }
    ++steps;
    left = std::chrono::steady_clock::now();
  }
  void report(const std::string& who) {
    if (!on || steps == 0) return;
    auto quote = [](const char* name, std::vector<float> v) {
      if (v.empty()) return;
      std::sort(v.begin(), v.end());
      std::fprintf(stderr, " %s %.1f / %.1f", name, 1000.0 * v[v.size() / 2], 1000.0 * v[(v.size() - 1) * 99 / 100]);
    };
    std::fprintf(stderr, "cuda profile (%s, %d solved steps), median / p99 us per stage:", who.c_str(), steps);
    for (int i = 0; i < kStages; ++i) quote(names[i], ms[i]);
    quote("between-steps(host)", between);
    std::fprintf(stderr, "\n");
  }
  ~Profiler() {
    for (auto& e : ev)
      if (e) cudaEventDestroy(e);
  }
};

/// The persistent kernel's phases (CudaTuning::phases, pcg.cu's PhaseClock): printed when
/// the backend dies, each phase's time in all, how often it ended, and its mean.
struct PhaseTimes {
  DeviceArray<unsigned long long> acc;  // PcgArgs::phase
  void init(bool enable, cudaStream_t s) {
    if (!enable) return;
    acc.alloc(2 * kPhases + 2);
    acc.zero(s);
  }
  void report(const std::string& who, cudaStream_t s) const {
    if (!acc.get()) return;
    std::vector<unsigned long long> v(acc.size());
    CU(cudaMemcpyAsync(v.data(), acc.get(), v.size() * sizeof(v[0]), cudaMemcpyDeviceToHost, s));
    CU(cudaStreamSynchronize(s));
    const double cycles = double(v[2 * kPhases + 1]);
    if (cycles <= 0) return;
    const double us_per_cycle = 1e-3 * double(v[2 * kPhases]) / cycles;
    static const char* names[kPhLevel] = {"start",     "cg-pressure", "cg-product", "cg-update",
                                          "mg-jacobi", "mg-pressure", "mg-product", "mg-restrict",
                                          "mg-prolong", "mg-coarsest", "mg-dot",    "finish"};
    static const char* level_names[4] = {"jacobi", "product", "restrict", "prolong"};
    std::fprintf(stderr, "cuda phases (%s): %.1f ms in launches; phase: total ms, times, mean us\n", who.c_str(),
                 1e-6 * double(v[2 * kPhases]));
    for (int id = 0; id < kPhases; ++id) {
      if (v[std::size_t(kPhases + id)] == 0) continue;
      const std::string name = id < kPhLevel ? names[id]
                                             : "level" + std::to_string((id - kPhLevel) / 4 + 1) + "-" +
                                                   level_names[(id - kPhLevel) % 4];
      const double ms = 1e-3 * us_per_cycle * double(v[std::size_t(id)]);
      const double n = double(v[std::size_t(kPhases + id)]);
      std::fprintf(stderr, "  %-16s %10.2f %10.0f %8.2f\n", name.c_str(), ms, n, 1e3 * ms / n);
    }
  }
};

template <class T>
class CudaBackend final : public Backend {
 public:
  /// A backend made by make_shadow for the converged check beside another's steps.
  struct Beside {
    bool on = false;
    int sms = 0;    // its solve on this many multiprocessors; 0: launched as the steps' are
    int slice = 0;     // ... then in slices of this many CG iterations (step_on); 0: in one
    int slice_mg = 0;  // ... or of this many where it borrows the multigrid levels
  };

  /// `shadow.on`: the converged check's backend beside another (make_shadow): its stream at
  /// the device's lowest priority, every other backend's at the highest, so that the
  /// steps' blocks are scheduled first where both wait for room.
  CudaBackend(const Model& model, const SimParams& params, Solver solver, Beside shadow = {})
      : m_(model), p_(resolved_for(model, params, solver == Solver::Persistent)), solver_(solver) {
    const DeviceInfo& d = device_info();
    if (!d.ok) throw std::runtime_error("cuda backend: " + d.why);
    if (amg::eigen_max_align_bytes() != EIGEN_MAX_ALIGN_BYTES)
      throw std::runtime_error("cuda backend: built with Eigen aligned to " + std::to_string(EIGEN_MAX_ALIGN_BYTES) +
                               " bytes in the CUDA sources and " + std::to_string(amg::eigen_max_align_bytes()) +
                               " in the C++ ones (give both the same -march)");
    check_element();  // before anything is allocated: a throwing constructor frees nothing
    if (const std::string no = library_baseline_refusal(name(), p_); !no.empty()) throw std::runtime_error(no);
    const CudaTuning tuning = CudaTuning::from_environment();
    tuning_ = tuning;
    CU(cudaSetDevice(d.device));
    int least = 0, greatest = 0;
    CU(cudaDeviceGetStreamPriorityRange(&least, &greatest));
    CU(cudaStreamCreateWithPriority(&stream_, cudaStreamNonBlocking, shadow.on ? least : greatest));
    CU(cudaEventCreateWithFlags(&done_, cudaEventDisableTiming));
    nn_ = m_.num_nodes();
    ne_ = m_.num_tets();
    nf_ = m_.num_free();
    nb_ = m_.num_blocks();
    ns_ = static_cast<int>(m_.surface_nodes.size());
    nt_ = static_cast<int>(m_.surface.size());
    if (static_cast<long long>(ne_) >= (1ll << 27)) throw std::runtime_error("cuda backend: too many elements");
    HostLayout<T> L(m_);
    tets_.upload(L.tets, stream_);
    grad_.upload(L.grad, stream_);
    vol_.upload(L.vol, stream_);
    block_row_.upload(L.block_row, stream_);
    pair_ptr_.upload(L.pair_ptr, stream_);
    pairs_.upload(L.pairs, stream_);
    upload_diag_block();
    free_surf_.upload(L.free_surf, stream_);
    {
      std::vector<int> tri(3 * std::size_t(nt_)), node_surf(nn_, -1);
      for (int t = 0; t < nt_; ++t)
        for (int k = 0; k < 3; ++k) tri[3 * std::size_t(t) + k] = m_.surface[t][k];
      for (int s = 0; s < ns_; ++s) node_surf[m_.surface_nodes[s]] = s;
      tri_.upload(tri, stream_);
      node_surf_.upload(node_surf, stream_);
      dof_.upload(m_.dof, stream_);
    }
    mass_.upload(L.mass, stream_);
    row_ptr_.upload(m_.row_ptr, stream_);
    col_.upload(m_.col, stream_);
    free_nodes_.upload(m_.free_nodes, stream_);
    x_.alloc(3 * std::size_t(nn_));
    v_.alloc(3 * std::size_t(nn_));
    quat_.alloc(4 * std::size_t(ne_));
    lambda_.alloc(ne_);
    mu_.alloc(ne_);
    rec_.alloc(kRec * std::size_t(ne_));
    vals_.alloc(9 * std::size_t(nb_));
    precond_.alloc(9 * std::size_t(nf_));
    for (auto* v : {&b_, &dv_, &dv_prev_, &r_, &z_, &p0_, &p1_, &q_}) v->alloc(3 * std::size_t(nf_));
    cA_.alloc(6 * std::size_t(std::max(ns_, 1)));
    cb_.alloc(3 * std::size_t(std::max(ns_, 1)));
    scratch_.alloc(1);
    // The result lives in mapped pinned memory: the kernels write it, no copy is queued.
    CU(cudaHostAlloc(reinterpret_cast<void**>(&host_res_), sizeof(DevResult), cudaHostAllocMapped));
    CU(cudaHostGetDevicePointer(reinterpret_cast<void**>(&dev_res_), host_res_, 0));
    rest_.resize(3 * std::size_t(nn_));
    for (int j = 0; j < nn_; ++j)
      for (int c = 0; c < 3; ++c) rest_[3 * j + c] = T(m_.rest[j][c]);
    rest_dev_.upload(rest_, stream_);
    upload_skin();
    detect_grid_ = cuda::detect_grid(nt_, d.sms);
    if (solver_ == Solver::Persistent) {
      launch_ = shadow.sms > 0 ? cuda::pcg_launch_confined<T>(shadow.sms, tuning) : cuda::pcg_launch<T>(nf_, tuning);
      slice_ = shadow.sms > 0 ? 0 : std::max(shadow.slice, 0);
      slice_mg_ = slice_ > 0 ? std::max(shadow.slice_mg, 1) : 0;
      cg_form_ = tuning.cg_form;
      // The one-reduction form's five further vectors, here rather than in the step that
      // first takes it, and only where pcg_form may choose it (not beside the large
      // meshes' streamed rows: 9.8 MB on xfine).
      if (cg_form_ == CudaTuning::CgForm::OneReduction || (cg_form_ == CudaTuning::CgForm::Auto && launch_.cached))
        for (auto& e : ext_) e.alloc(3 * std::size_t(nf_));
    } else {
#ifdef PALPATION_HAVE_CUSPARSE
      baseline_ = solver_ == Solver::Csr ? cuda::make_csr_baseline<T>(m_, pcg_args(), stream_)
                                         : cuda::make_bsr_baseline<T>(m_, pcg_args(), stream_);
#else
      throw std::runtime_error("backend " + name() + ": this build has no cuSPARSE/cuBLAS");
#endif
    }
    prof_.init(tuning.profile);
    phases_.init(tuning.phases, stream_);
    set_materials(m_.materials);
    reset();
  }

  ~CudaBackend() override {
    prof_.report(name() + (std::is_same_v<T, double> ? " double" : " float"));
    try {
      if (stream_) phases_.report(name() + (std::is_same_v<T, double> ? " double" : " float"), stream_);
    } catch (const std::exception& e) {  // a destructor does not throw; the report is a measurement's only
      std::fprintf(stderr, "cuda phases: %s\n", e.what());
    }
    baseline_.reset();  // its cuSPARSE/cuBLAS handles work in stream_: gone before the stream
    if (stream_) cudaStreamSynchronize(stream_);  // a take begun and never finished
    if (host_res_) cudaFreeHost(host_res_);
    if (done_) cudaEventDestroy(done_);
    if (stream_) cudaStreamDestroy(stream_);
  }

  std::string name() const override {
    return solver_ == Solver::Persistent ? "cuda" : (solver_ == Solver::Csr ? "cuda-csr" : "cuda-bsr");
  }
  std::string device_name() const override { return device_info().name; }
  Precision precision() const override { return std::is_same_v<T, double> ? Precision::Double : Precision::Float; }
  const SimParams& params() const override { return p_; }
  MultigridCounts multigrid_counts() const override { return multigrid_.with_smoother(multigrid_counts_); }
  void prepare_solver() override {
    if (!is_multigrid(p_.solver.preconditioner) || !rested_ || solver_ != Solver::Persistent) return;
    // The rest state's element pass and assembly, with no finger: what the first step's
    // would make of it (the rotations stay the identity, dv and its predecessor zero).
    const StepConsts k = step_consts();
    launch_element(FingersArg{}, k, false);
    launch_assemble(k, false);
    launch_skin(k);
    if (nodal()) launch_pressure();
    use_multigrid(false);
    CU(cudaStreamSynchronize(stream_));
  }
  void set_deferred_levels(bool on) override { multigrid_.set_deferred(on); }
  std::shared_ptr<LevelsJob> take_levels_job() override { return multigrid_.take_job(); }
  bool install_levels(const std::shared_ptr<LevelsJob>& job) override {
    // Between steps (the last one's result fetched): the old levels' buffers are free to go.
    CU(cudaStreamSynchronize(stream_));
    return multigrid_.install(job, [&](const amg::Hierarchy& levels) { upload_levels(levels); },
                              multigrid_counts_.builds, multigrid_counts_.failures);
  }
  void set_params(const SimParams& given) override {
    const SimParams p = resolved_for(m_, given, solver_ == Solver::Persistent);
    // A body at rest is at rest under the parameters it settled with: a new gravity (or
    // anything else but dt and threads) is solved for.
    if (differ_beyond_step(p, p_)) rested_ = false;
    if (const std::string no = library_baseline_refusal(name(), p); !no.empty()) throw std::runtime_error(no);
    const bool element_changed = p.element != p_.element;
    if (p.solver.preconditioner != p_.solver.preconditioner) multigrid_.invalidate();
    const SimParams old = p_;
    p_ = p;
    if (element_changed) {
      try {
        set_materials(mat_);
      } catch (...) {
        p_ = old;  // the backend stays as it was
        throw;
      }
    }
  }

  void set_materials(const Materials& mat) override {
    const bool nodal = p_.element == Element::NodalPressure;
    check_element();
    if (&mat != &mat_) mat_ = mat;
    std::vector<T> l(ne_), mu(ne_);
    for (int e = 0; e < ne_; ++e) {
      l[e] = nodal ? T(0) : T(mat.lambda[e]);  // the nodal-pressure element: lambda in its nodal term
      mu[e] = T(mat.mu[e]);
    }
    CU(cudaStreamSynchronize(stream_));
    lambda_.upload(l, stream_);
    mu_.upload(mu, stream_);
    if (nodal) {
      upload_pressure_pattern();
      const std::vector<double> w = nodal_pressure_weights(m_, *np_, mat.lambda);
      npw_.upload(std::vector<T>(w.begin(), w.end()), stream_);
      npw_host_ = w;
    }
    multigrid_.invalidate();  // another system: the multigrid levels are built again
    rested_ = false;
  }

  void reset() override {
    CU(cudaStreamSynchronize(stream_));
    x_.upload(rest_, stream_);
    v_.zero(stream_);
    dv_.zero(stream_);
    dv_prev_.zero(stream_);
    last_converged_ = false;
    tight_solves_ = 0;
    has_kept_ = false;
    reuse_pending_ = false;
    pending_ = Pending::None;  // a take begun is dropped (the stream was waited for above)
    multigrid_.invalidate();
    p0_.zero(stream_);
    p1_.zero(stream_);
    std::vector<T> q(4 * std::size_t(ne_), T(0));
    for (int e = 0; e < ne_; ++e) q[4 * std::size_t(e)] = T(1);
    CU(cudaMemcpyAsync(quat_.get(), q.data(), sizeof(T) * q.size(), cudaMemcpyHostToDevice, stream_));
    scratch_.zero(stream_);
    cA_.zero(stream_);
    cb_.zero(stream_);
    CU(cudaStreamSynchronize(stream_));
    std::memset(static_cast<void*>(host_res_), 0, sizeof(DevResult));
    filtered_.clear();
    rested_ = p_.gravity.squaredNorm() == 0;
  }

  void positions(std::vector<double>& xyz) const override { xyz = x_.to_host_double(stream_); }
  void velocities(std::vector<double>& xyz) const override { xyz = v_.to_host_double(stream_); }

  // Device-to-device copies in stream order: the next step's kernels follow them.
  bool checkpoint() override {
    has_kept_ = true;
    kept_x_.copy_from(x_, stream_);
    kept_v_.copy_from(v_, stream_);
    kept_quat_.copy_from(quat_, stream_);
    kept_dv_.copy_from(dv_, stream_);
    kept_dv_prev_.copy_from(dv_prev_, stream_);
    kept_filtered_ = filtered_;
    kept_rested_ = rested_;
    kept_last_converged_ = last_converged_;
    kept_tight_solves_ = tight_solves_;
    return true;
  }
  void rollback() override {
    if (!has_kept_) return;
    x_.copy_from(kept_x_, stream_);
    v_.copy_from(kept_v_, stream_);
    quat_.copy_from(kept_quat_, stream_);
    dv_.copy_from(kept_dv_, stream_);
    dv_prev_.copy_from(kept_dv_prev_, stream_);
    filtered_ = kept_filtered_;
    rested_ = kept_rested_;
    last_converged_ = kept_last_converged_;
    tight_solves_ = kept_tight_solves_;
  }
  void rollback_for_reference() override {
    if (!has_kept_) return;
    reuse_dv_.copy_from(dv_, stream_);  // the undone take's solution, before dv_ is restored
    rollback();
    reuse_pending_ = true;
  }

  // The persistent solve only: the baselines' host-driven loops would wait in begin_step.
  // Both solves are cooperative launches, which start only when all their blocks fit at
  // once: a shadow launched as the steps' are takes turns with them, each check holding a
  // step up for the length of its reference solve. So the shadow's solve gets the
  // multiprocessors the steps' solve leaves (CudaTuning::shadow_sms keeps some), one block
  // each, and never waits for the steps or makes them wait (on the paper mesh the steps'
  // solve is a grid of 119 blocks; the H200 has 132 multiprocessors). Where the steps'
  // solve fills the device (xfine and up), the shadow takes the whole device a slice at a
  // time: its element pass and assembly, then CudaTuning::shadow_slice CG iterations a
  // launch (shadow_slice_mg with the steps' multigrid levels, which it borrows: see
  // fork_reference), each queued after one of the steps (step_on), so that a check holds a
  // step up by one slice instead of a whole reference solve.
  std::unique_ptr<Backend> make_shadow(const SimParams& params) const override {
    if (solver_ != Solver::Persistent) return nullptr;
    using Place = CudaTuning::ShadowPlace;
    const int spare = spare_sms();
    if (params.solver.check == CheckPlace::Auto && spare < 1 && tuning_.shadow_place == Place::Full) return nullptr;
    Beside beside{true, 0, 0};
    if (tuning_.shadow_place == Place::Confined && spare >= 1)
      beside.sms = spare;
    else if (tuning_.shadow_place != Place::Full) {
      beside.slice = tuning_.shadow_slice;
      beside.slice_mg = tuning_.shadow_slice_mg;
    }
    auto s = std::make_unique<CudaBackend<T>>(m_, params, solver_, beside);
    s->set_materials(mat_);
    return s;
  }
  // The multiprocessors that neither of the steps' solves (block-Jacobi, multigrid) takes.
  int spare_sms() const {
    const int taken = std::max(launch_.sms, mg_launch_.fn ? mg_launch_.sms : cuda::pcg_launch<T>(nf_, tuning_, true).sms);
    return device_info().sms - taken;
  }
  // Device-to-device copies in this backend's stream, after its take; the shadow's stream
  // waits for them, and this stream's next step (which overwrites the live state, never the
  // checkpoint) follows them.
  bool fork_reference(Backend& shadow) override {
    auto* s = dynamic_cast<CudaBackend<T>*>(&shadow);
    if (!s || s == this || &s->m_ != &m_ || !has_kept_ || solver_ != Solver::Persistent || s->pending_ != Pending::None) return false;
    CU(cudaStreamSynchronize(s->stream_));  // nothing of the shadow's own in flight
    s->x_.copy_from(kept_x_, stream_);
    s->v_.copy_from(kept_v_, stream_);
    s->quat_.copy_from(kept_quat_, stream_);
    s->dv_.copy_from(kept_dv_, stream_);
    s->dv_prev_.copy_from(kept_dv_prev_, stream_);
    s->kept_dv_.copy_from(kept_dv_, stream_);  // what its take keeps as the previous solution
    s->reuse_dv_.copy_from(dv_, stream_);
    CU(cudaEventRecord(done_, stream_));
    CU(cudaStreamWaitEvent(s->stream_, done_, 0));
    // A shadow in slices solves with this one's multigrid levels where its take used them
    // (the levels are a preconditioner: those of the last step fit the checkpoint's system
    // as they fit the next step's): a reference in a few V-cycles instead of block-Jacobi's
    // many iterations (xfine), with no levels built for it. Confined shadows keep
    // block-Jacobi: their few multiprocessors would make a V-cycle's many barriers dear.
    s->borrowed_mg_ = s->slice_ > 0 && begun_mg_ && mg_levels_.dev();
    if (s->borrowed_mg_) {
      s->mg_levels_.borrow(mg_levels_, s->stream_, std::is_same_v<T, float>);
      s->prepare_mg_solve();
    }
    s->filtered_ = kept_filtered_;
    s->rested_ = kept_rested_;
    s->last_converged_ = kept_last_converged_;
    s->tight_solves_ = kept_tight_solves_;
    s->reuse_pending_ = true;
    s->has_kept_ = false;
    return true;
  }

  StepStats step(std::span<const FingerInput> fingers, std::span<FingerOutput> out) override {
    begin_step(fingers);
    return finish_step(out);
  }

  // The solve's launches are queued and the step's end (its statistics, the finger
  // outputs) waits for finish_step(). At rest the detection decides at once, as in step().
  void begin_step(std::span<const FingerInput> fingers) override {
    if (fingers.size() > std::size_t(kMaxFingers))
      throw std::runtime_error("cuda backend: at most " + std::to_string(kMaxFingers) + " fingers");
    if (pending_ != Pending::None) throw std::logic_error("cuda backend: a take begun twice");
    begun_fingers_.assign(fingers.begin(), fingers.end());
    if (filtered_.size() != fingers.size()) filtered_.assign(fingers.size(), Eigen::Vector3d::Zero());
    const FingersArg F = fingers_arg(fingers);
    const StepConsts k = step_consts();

    const bool reuse = std::exchange(reuse_pending_, false);  // rollback_for_reference() just before
    bool detected = false;
    if (rested_) {
      // At rest: the solve is needed only if something touches. Detection on the GPU and
      // the result in mapped memory: one launch and one synchronisation decide.
      launch_detect(F, k, true);
      fetch_result();
      if (host_res_->start_contacts == 0) {
        pending_ = Pending::Rest;
        return;
      }
      detected = true;
    }
    prof_.mark(0, stream_);
    launch_element(F, k, !detected);
    prof_.mark(1, stream_);
    // After rollback_for_reference(): from the undone take's solution, not extrapolated; the
    // assembly then keeps it as the previous solution, which is the checkpoint's instead
    // (what the next step extrapolates from, as after any take).
    if (reuse) dv_.copy_from(reuse_dv_, stream_);
    launch_assemble(k, !reuse && warm_start_extrapolates(p_.solver.warm_start, last_converged_, tight_solves_));
    if (reuse) dv_prev_.copy_from(kept_dv_, stream_);
    launch_skin(k);
    if (nodal()) launch_pressure();
    prof_.mark(2, stream_);
    begun_mg_ = solver_ == Solver::Persistent && (borrowed_mg_ || use_multigrid());
    slices_launched_ = 0;
    if (slice_ > 0) {
      // In slices: this one is the element pass and assembly; step_on() queues the solve's.
    } else if (solver_ == Solver::Persistent) {
      launch_pcg(F, k, begun_mg_);
    } else {
      baseline_->solve(pcg_args(), begun_iterations_, begun_residual_);
      launch_detect(F, k, false);
    }
    prof_.mark(3, stream_);
    CU(cudaEventRecord(done_, stream_));
    pending_ = Pending::Solve;
  }

  bool step_ready() const override {
    if (pending_ != Pending::Solve) return true;
    const cudaError_t e = launches_done();
    if (e == cudaErrorNotReady) return false;
    return e != cudaSuccess || slice_ == 0 || !slices_remain();  // an error: finish_step reports it
  }

  void step_on() override {
    if (pending_ == Pending::Solve && slice_ > 0 && launches_done() == cudaSuccess && slices_remain()) launch_slice();
  }

  StepStats finish_step(std::span<FingerOutput> out) override {
    if (pending_ == Pending::Solve && slice_ > 0)
      for (;;) {
        CU(cudaEventSynchronize(done_));
        if (!slices_remain()) break;
        launch_slice();
      }
    StepStats st;
    const std::span<const FingerInput> fingers = begun_fingers_;
    const Pending was = std::exchange(pending_, Pending::None);
    if (was == Pending::None) throw std::logic_error("cuda backend: no take begun");
    if (was == Pending::Rest) {
      finger_outputs(fingers, out);
      st.contacts = 0;
      st.finite = true;
      for (const auto& o : out) st.finite = st.finite && o.force.allFinite();
      return st;
    }
    int iterations = begun_iterations_;
    double residual = begun_residual_;
    const bool mg = begun_mg_;
    fetch_result();
    prof_.mark(4, stream_);
    if (prof_.on) {
      CU(cudaEventSynchronize(prof_.ev[4]));
      prof_.collect();
    }
    const DevResult& R = *host_res_;
    if (solver_ == Solver::Persistent) {
      iterations = R.cg_iterations;
      residual = R.cg_residual;
    }
    st.cg_iterations = iterations;
    st.cg_residual = residual;
    // A solve beyond its tolerance and the rescue tolerance says the levels no longer fit.
    // (Not for levels borrowed from another backend: that one's own solves judge them.)
    if (mg && !borrowed_mg_)
      multigrid_.note(iterations, residual <= std::max(p_.solver.cg_tolerance, p_.solver.cg_rescue_tolerance),
                      p_.solver.cg_tolerance);
    // The next step extrapolates its warm start only after a converged solve (WarmStart::Last:
    // two tight ones, params.h): with the iterations capped below convergence,
    // extrapolating the truncation error doubles it, and so it does a loose solve's.
    last_converged_ = residual <= p_.solver.cg_tolerance;
    tight_solves_ = count_tight_solves(tight_solves_, residual);
    st.rescued = iterations > p_.solver.cg_max_iterations;
    st.solved = true;
    st.contacts = R.start_contacts;
    rested_ = R.rested != 0;
    st.finite = std::isfinite(R.vmax) && std::isfinite(residual);
    const bool finite_v = std::isfinite(R.v2max) && std::isfinite(R.ke);
    st.max_speed = finite_v ? std::sqrt(R.v2max) : INFINITY;
    st.max_displacement = finite_v && std::isfinite(R.d2max) ? std::sqrt(R.d2max) : INFINITY;
    st.kinetic_energy = finite_v ? (rested_ ? 0.0 : R.ke) : INFINITY;
    if (rested_) st.max_speed = 0;
    finger_outputs(fingers, out);
    for (const auto& o : out) st.finite = st.finite && o.force.allFinite();
    return st;
  }

 private:
  void fetch_result() { CU(cudaStreamSynchronize(stream_)); }

  bool nodal() const { return p_.element == Element::NodalPressure; }

  /// The library baselines (baseline.cu) have the linear element only.
  void check_element() const {
    if (nodal() && solver_ != Solver::Persistent)
      throw std::runtime_error("backend " + name() + ": tissue.element \"nodal-pressure\" runs on the cpu and cuda backends");
  }

  /// The nodal-pressure term's pattern (once), its element incidences over every node and
  /// its scratch, on the device.
  void upload_pressure_pattern() {
    if (np_) return;
    np_ = std::make_shared<const NodalPressurePattern>(build_nodal_pressure_pattern(m_));
    levels_pattern_.reset();  // made again with np_
    np_row_ptr_.upload(np_->row_ptr, stream_);
    np_col_.upload(np_->col, stream_);
    np_t_row_ptr_.upload(np_->t_row_ptr, stream_);
    np_t_node_.upload(np_->t_node, stream_);
    np_t_pair_.upload(np_->t_pair, stream_);
    // Incidence lists in CSR form: count, prefix-sum, fill.
    auto incidences = [](int rows, auto each, std::vector<int>& ptr, std::vector<int>& list) {
      ptr.assign(rows + 1, 0);
      each([&](int row, int) { ++ptr[row + 1]; });
      for (int r = 0; r < rows; ++r) ptr[r + 1] += ptr[r];
      list.resize(ptr[rows]);
      std::vector<int> fill(ptr.begin(), ptr.end() - 1);
      each([&](int row, int v) { list[fill[row]++] = v; });
    };
    // The free nodes' pairs are formed by the assembly, block by block: the pair of each
    // block (n = its row's node, j = its column). The fixed nodes' pairs (the chest wall's
    // rows, in the pair order) by k_pressure_pairs, over the elements holding each.
    std::vector<int> block_pair(nb_), fixed;
    for (int i = 0; i < nf_; ++i)
      for (int k = m_.row_ptr[i]; k < m_.row_ptr[i + 1]; ++k) {
        block_pair[k] = np_->pair_of(m_.free_nodes[i], m_.col[k]);
        if (block_pair[k] < 0) throw std::logic_error("cuda backend: a block without its nodal-pressure pair");
      }
    std::vector<int> fixed_slot(std::size_t(np_->num_pairs()), -1);
    for (int n : np_->fixed_rows)
      for (int k = np_->row_ptr[n]; k < np_->row_ptr[n + 1]; ++k) {
        fixed_slot[std::size_t(k)] = int(fixed.size());
        fixed.push_back(k);
      }
    np_block_pair_.upload(block_pair, stream_);
    np_fixed_pairs_.upload(fixed, stream_);
    np_nfixed_ = int(fixed.size());
    // The elements holding each fixed pair (n, j), by its slot in `fixed`: e << 2 | b, j
    // element e's node b.
    std::vector<int> ptr, list;
    incidences(
        np_nfixed_,
        [&](auto add) {
          for (int e = 0; e < ne_; ++e)
            for (int k = 0; k < 16; ++k)
              if (const int pair = np_->tet_pair[e][k]; pair >= 0 && fixed_slot[std::size_t(pair)] >= 0)
                add(fixed_slot[std::size_t(pair)], (e << 2) | (k & 3));
        },
        ptr, list);
    np_pinc_ptr_.upload(ptr, stream_);
    np_pinc_.upload(list, stream_);
    incidences(
        nn_,
        [&](auto add) {
          for (int e = 0; e < ne_; ++e)
            for (int a = 0; a < 4; ++a) add(m_.tets[e][a], e);
        },
        ptr, list);
    np_inc_ptr_.upload(ptr, stream_);
    np_inc_.upload(list, stream_);
    upload_diag_block();
    npb_.alloc(3 * std::size_t(np_->num_pairs()));
    npi_.alloc(nn_);
    np_rest_part_.alloc(ne_);
  }

  // The skin membrane's triangles, rest data and where their blocks and rows lie in the
  // device system (assembly.cuh's layout).
  void upload_skin() {
    const SkinMembrane& sk = m_.skin;
    nskin_ = sk.size();
    if (nskin_ == 0) return;
    std::vector<int> tri(3 * std::size_t(nskin_)), row(3 * std::size_t(nskin_)), base(9 * std::size_t(nskin_)),
        stride(9 * std::size_t(nskin_));
    std::vector<membrane::Rest<T>> rest(static_cast<std::size_t>(nskin_));
    std::vector<unsigned char> under(std::size_t(nf_), 0);
    for (int t = 0; t < nskin_; ++t) {
      const std::size_t ts = std::size_t(t);
      rest[ts] = membrane::rest_cast<T>(sk.rest[ts]);
      for (int a = 0; a < 3; ++a) {
        const int node = sk.triangles[ts][std::size_t(a)], i = m_.dof[std::size_t(node)];
        tri[3 * ts + a] = node;
        row[3 * ts + a] = i < 0 ? -1 : 3 * i;
        if (i >= 0) under[std::size_t(i)] = 1;
      }
      for (int a = 0; a < 3; ++a) {
        const int i = m_.dof[std::size_t(sk.triangles[ts][std::size_t(a)])];
        for (int b = 0; b < 3; ++b) {
          const int blk = sk.block[ts][std::size_t(3 * a + b)];
          const std::size_t ab = 9 * ts + std::size_t(3 * a + b);
          if (blk < 0) {
            base[ab] = -1;
            stride[ab] = 0;
            continue;
          }
          const int k0 = m_.row_ptr[std::size_t(i)];
          base[ab] = 9 * k0 + 3 * (blk - k0);
          stride[ab] = 3 * (m_.row_ptr[std::size_t(i) + 1] - k0);
        }
      }
    }
    std::vector<int> skin_free;
    for (int i = 0; i < nf_; ++i)
      if (under[std::size_t(i)]) skin_free.push_back(i);
    if (static_cast<long long>(9) * nb_ >= (1ll << 31)) throw std::runtime_error("cuda backend: too many blocks for the skin");
    skin_tri_.upload(tri, stream_);
    skin_row_.upload(row, stream_);
    skin_base_.upload(base, stream_);
    skin_stride_.upload(stride, stream_);
    skin_rest_.upload(rest, stream_);
    skin_free_.upload(skin_free, stream_);
    upload_diag_block();
  }

  // Each free row's diagonal block index, for the stages that re-invert diagonal blocks
  // themselves (the nodal pressure and the skin): once for both.
  void upload_diag_block() {
    if (diag_block_.size() != m_.diag_block.size()) diag_block_.upload(m_.diag_block, stream_);
  }

  void launch_skin(const StepConsts& k) {
    if (nskin_ == 0) return;
    const SkinMembrane& sk = m_.skin;
    SkinArgs<T> a{};
    a.ntri = nskin_;
    a.tri = skin_tri_.get();
    a.rest = skin_rest_.get();
    a.row = skin_row_.get();
    a.base = skin_base_.get();
    a.stride = skin_stride_.get();
    a.x = x_.get();
    a.v = v_.get();
    a.lambda_p = T(sk.lambda_plane());
    a.mu = T(sk.mu());
    const T h = T(k.h);
    a.h = h;
    a.damp = T(k.beta) + h;
    a.kscale = h * h + h * T(k.beta);
    a.vals = vals_.get();
    a.b = b_.get();
    a.nskin_free = static_cast<int>(skin_free_.size());
    a.skin_free = skin_free_.get();
    a.row_ptr = row_ptr_.get();
    a.diag_block = diag_block_.get();
    a.precond = precond_.get();
    cuda::launch_skin(stream_, a, !nodal());
  }

  PressureDev<T> pressure_dev() {
    PressureDev<T> P;
    if (!nodal()) return P;
    const T h = T(p_.solver.dt);
    P.row_ptr = np_row_ptr_.get();
    P.col = np_col_.get();
    P.t_row_ptr = np_t_row_ptr_.get();
    P.t_node = np_t_node_.get();
    P.t_pair = np_t_pair_.get();
    P.b = npb_.get();
    P.w = npw_.get();
    P.pi = npi_.get();
    P.scale = h * h + h * T(p_.damping.stiffness);
    return P;
  }

  void launch_pressure() {
    PressureArgs<T> a{};
    a.P = pressure_dev();
    a.nnode = nn_;
    a.nf = nf_;
    a.nfixed = np_nfixed_;
    a.fixed_pairs = np_fixed_pairs_.get();
    a.pinc_ptr = np_pinc_ptr_.get();
    a.pinc = np_pinc_.get();
    a.ninc_ptr = np_inc_ptr_.get();
    a.ninc = np_inc_.get();
    a.rec = rec_.get();
    a.vol = vol_.get();
    a.rest_part = np_rest_part_.get();
    a.free_nodes = free_nodes_.get();
    a.x = x_.get();
    a.v = v_.get();
    a.rest = rest_dev_.get();
    a.h = T(p_.solver.dt);
    a.damp = T(p_.damping.stiffness) + a.h;
    a.row_ptr = row_ptr_.get();
    a.diag_block = diag_block_.get();
    a.vals = vals_.get();
    a.b = b_.get();
    a.precond = precond_.get();
    cuda::launch_pressure(stream_, a);
  }

  DetectArgs<T> detect_args() {
    return DetectArgs<T>{nt_,      tri_.get(), node_surf_.get(), dof_.get(), ns_,     x_.get(),
                         v_.get(), cA_.get(), cb_.get(),        scratch_.get(), dev_res_};
  }

  void launch_detect(const FingersArg& F, const StepConsts& k, bool start) {
    cuda::launch_detect(stream_, detect_grid_, detect_args(), F, k, start);
  }

  /// Elements, plus the start-of-step contact detection in extra blocks when `detect`.
  void launch_element(const FingersArg& F, const StepConsts& k, bool detect) {
    ElementArgs<T> a{ne_, tets_.get(), grad_.get(), vol_.get(), lambda_.get(), mu_.get(), quat_.get(), x_.get(), v_.get(),
                     rec_.get(), T(k.h), T(k.beta), 0};  // elem_blocks: set by launch_element
    if (nodal()) a.rest_part = np_rest_part_.get();
    cuda::launch_element(stream_, a, detect_args(), F, k, detect);
  }

  StepConsts step_consts() const {
    StepConsts k{};
    k.h = p_.solver.dt;
    k.alpha = p_.damping.mass;
    k.beta = p_.damping.stiffness;
    k.ks = p_.contact.stiffness;
    k.ke = p_.contact.damping;
    for (int c = 0; c < 3; ++c) k.g[c] = p_.gravity[c];
    return k;
  }

  void launch_assemble(const StepConsts& k, bool extrapolate) {
    AssembleArgs<T> a{};
    a.nf = nf_;
    a.nb = nb_;
    a.row_ptr = row_ptr_.get();
    a.block_row = block_row_.get();
    a.diag_block = diag_block_.get();
    a.pair_ptr = pair_ptr_.get();
    a.pairs = pairs_.get();
    a.rec = rec_.get();
    if (nodal()) {
      a.pres_b = npb_.get();
      a.pres_pair = np_block_pair_.get();
      a.vol = vol_.get();
    }
    a.free_nodes = free_nodes_.get();
    a.free_surf = free_surf_.get();
    a.mass = mass_.get();
    a.v = v_.get();
    a.cA = cA_.get();
    a.cb = cb_.get();
    a.vals = vals_.get();
    a.precond = precond_.get();
    a.invert = nodal() ? 0 : 1;  // k_pressure_free inverts every block with its term
    a.b = b_.get();
    a.dv = dv_.get();
    a.dv_prev = dv_prev_.get();
    a.extrapolate = extrapolate ? 1 : 0;
    const T h = T(k.h);
    a.kscale = h * h + h * T(k.beta);
    a.mscale = T(1) + h * T(k.alpha);
    a.h = h;
    a.alpha = T(k.alpha);
    a.g0 = T(k.g[0]);
    a.g1 = T(k.g[1]);
    a.g2 = T(k.g[2]);
    cuda::launch_assemble(stream_, a);
  }

  /// The multigrid levels for this step's solve, built (on the host, from the system
  /// assembled on the device) and copied to the device when due (multigrid_keeper.h); false:
  /// block-Jacobi.
  bool use_multigrid(bool may_defer = true) {
    const T h = T(p_.solver.dt);
    const T scale = h * h + h * T(p_.damping.stiffness);  // as the CPU backend's system
    return multigrid_.prepare(
        p_.solver.preconditioner, double(scale), m_,
        [&]() -> LevelsSystem {
          // The step only queues device-to-device copies of what it assembled (a fraction
          // of a millisecond); the read-back (a tenth of a second on xfine) and the sorting
          // into a sparse matrix are done where the system is made.
          if (!levels_pattern_)  // np_ as it is (none until an element needs it: made again then)
            levels_pattern_ = std::make_shared<const LevelsPattern>(LevelsPattern{nf_, m_.row_ptr, m_.col, np_});
          if (!system_copy_ || system_copy_.use_count() > 1)  // a build still reads the last one
            system_copy_ = std::make_shared<SystemCopy>(device_info().device);
          const std::shared_ptr<SystemCopy> copy = system_copy_;
          copy->vals.copy_from(vals_, stream_);
          std::vector<double> w;
          if (nodal()) {
            copy->b.copy_from(npb_, stream_);
            // The weights as the device holds them (in T), as the CPU backend builds from its own.
            w.resize(npw_host_.size());
            for (std::size_t i = 0; i < w.size(); ++i) w[i] = double(T(npw_host_[i]));
          }
          CU(cudaEventRecord(copy->ready, stream_));
          const double pressure_scale = nodal() ? double(pressure_dev().scale) : 0.0;
          return [pattern = levels_pattern_, copy, w = std::move(w), pressure_scale](amg::SpMat& stiffness,
                                                                                     amg::SpMat& pressure) {
            stiffness = block_rows_to_sparse(pattern->nf, pattern->row_ptr, pattern->col, copy->read(copy->vals));
            if (!w.empty()) pressure = nodal_pressure_to_sparse(*pattern->np, pattern->nf, copy->read(copy->b), w, pressure_scale);
          };
        },
        [&](const amg::Hierarchy& levels) { upload_levels(levels); }, multigrid_counts_.builds,
        multigrid_counts_.failures, may_defer);
  }
  // The levels' copy on the device. A CUDA error here is the device's, not the levels': it
  // goes to the caller.
  void upload_levels(const amg::Hierarchy& levels) {
    prepare_mg_solve();  // the launch, whose threads choose the products' lanes
    mg_levels_.upload(levels, stream_, long(mg_launch_.grid) * mg_launch_.block, tuning_.mg_lanes, std::is_same_v<T, float>);
  }
  // The multigrid solve's launch and its finest level's scratch, once.
  void prepare_mg_solve() {
    if (!mg_launch_.fn) mg_launch_ = cuda::pcg_launch<T>(nf_, tuning_, true);
    if (mg_r_.size() != 3 * std::size_t(nf_)) {
      mg_r_.alloc(3 * std::size_t(nf_));
      mg_d_.alloc(3 * std::size_t(nf_));
    }
  }

  // The PCG's form (tuning.h, CgForm): three barriers when asked, or under `auto` with the
  // nodal-pressure term where the rows stream from memory because they are many (the large
  // meshes, not a confined shadow's few multiprocessors): p in a pass of its own costs less
  // than the pressures and the product reading z and the previous p at every neighbour.
  // The one-reduction form (block-Jacobi only) when asked, or under `auto` where it was
  // measured quicker: no nodal-pressure term and every row in registers. Two barriers
  // otherwise.
  PcgForm pcg_form(bool multigrid, bool nodal_pressure) const {
    using Form = CudaTuning::CgForm;
    const bool streamed = !launch_.confined && !(multigrid ? mg_launch_ : launch_).cached;
    if (cg_form_ == Form::ThreeBarriers || (cg_form_ == Form::Auto && nodal_pressure && streamed))
      return kThreeBarriers;
    if (slice_ > 0) return kTwoBarriers;  // the one-reduction form does not stop in slices
    const bool quicker = launch_.cached && !nodal_pressure;
    if (!multigrid && (cg_form_ == Form::OneReduction || (cg_form_ == Form::Auto && quicker))) return kOneReduction;
    return kTwoBarriers;
  }

  PcgArgs<T> pcg_args(bool multigrid = false) {
    PcgArgs<T> a{};
    a.n = nf_;
    a.row_ptr = row_ptr_.get();
    a.col = col_.get();
    a.vals = vals_.get();
    a.P = precond_.get();
    a.b = b_.get();
    a.x = dv_.get();
    a.r = r_.get();
    a.z = z_.get();
    a.p0 = p0_.get();
    a.p1 = p1_.get();
    a.q = q_.get();
    a.nnode = nn_;
    a.free_nodes = free_nodes_.get();
    a.xpos = x_.get();
    a.vel = v_.get();
    a.rest = rest_dev_.get();
    a.mass = mass_.get();
    a.h = T(p_.solver.dt);
    a.tol = T(p_.solver.cg_tolerance);
    a.max_it = p_.solver.cg_max_iterations;
    a.rescue_tol = T(p_.solver.cg_rescue_tolerance);
    a.rescue_it = p_.solver.cg_rescue_iterations;
    a.pres = pressure_dev();
    a.form = pcg_form(multigrid, a.pres.b != nullptr);
    if (a.form == kOneReduction)
      for (int e = 0; e < 5; ++e) a.ext[e] = ext_[e].get();
    a.scr = scratch_.get();
    a.res = dev_res_;
    a.phase = phases_.acc.get();
    if (multigrid) {
      a.mg = mg_levels_.dev();
      a.mg_r = mg_r_.get();
      a.mg_d = mg_d_.get();
    }
    return a;
  }

  // The fingers as the kernels take them.
  static FingersArg fingers_arg(std::span<const FingerInput> fingers) {
    FingersArg F{};
    F.n = static_cast<int>(fingers.size());
    for (int f = 0; f < F.n; ++f) {
      for (int c = 0; c < 3; ++c) {
        F.f[f].c[c] = fingers[f].position[c];
        F.f[f].v[c] = fingers[f].velocity[c];
      }
      F.f[f].r = fingers[f].radius;
      F.f[f].active = fingers[f].active ? 1 : 0;
    }
    return F;
  }

  // Whether the launches of the take begun have finished (never waits): cudaSuccess,
  // cudaErrorNotReady, or the error they met (cleared here: the next synchronisation,
  // finish_step's, reports it).
  cudaError_t launches_done() const {
    const cudaError_t e = cudaEventQuery(done_);
    if (e != cudaSuccess && e != cudaErrorNotReady) (void)cudaGetLastError();
    return e;
  }

  void launch_pcg(const FingersArg& F, const StepConsts& k, bool multigrid) {
    cuda::launch_pcg(stream_, multigrid ? mg_launch_ : launch_, pcg_args(multigrid), detect_args(), F, k);
  }

  // A take in slices, its last slice finished: whether the solve has more to go (none
  // launched yet, or the last one stopped short: DevResult::unfinished).
  bool slices_remain() const { return slices_launched_ == 0 || host_res_->unfinished != 0; }

  // The next slice of a take's solve: slice_ CG iterations, going on from the last.
  void launch_slice() {
    PcgArgs<T> a = pcg_args(begun_mg_);
    a.slice = begun_mg_ ? slice_mg_ : slice_;
    a.resume = slices_launched_ > 0 ? 1 : 0;
    cuda::launch_pcg(stream_, begun_mg_ ? mg_launch_ : launch_, a, detect_args(), fingers_arg(begun_fingers_), step_consts());
    ++slices_launched_;
    CU(cudaEventRecord(done_, stream_));
  }

  void finger_outputs(std::span<const FingerInput> fingers, std::span<FingerOutput> out) {
    const double a = force_filter_alpha(p_.contact.force_filter_hz, p_.solver.dt);
    for (std::size_t f = 0; f < out.size(); ++f) out[f] = FingerOutput{};
    for (std::size_t f = 0; f < out.size() && f < fingers.size(); ++f) {
      const double* s = host_res_->finger[f];
      FingerOutput& o = out[f];
      o.force_raw = Eigen::Vector3d(s[0], s[1], s[2]);
      o.stiffness << s[3], s[4], s[5], s[4], s[6], s[7], s[5], s[7], s[8];
      o.contacts = static_cast<int>(std::lround(s[12]));
      o.contact_point = Eigen::Vector3d(s[9], s[10], s[11]);
      finish_finger_output(o, filtered_[f], a);
    }
  }

  const Model& m_;
  SimParams p_;
  Solver solver_;
  int nn_ = 0, ne_ = 0, nf_ = 0, nb_ = 0, ns_ = 0, nt_ = 0;
  PcgLaunch launch_;
  int detect_grid_ = 1;
  CudaTuning::CgForm cg_form_ = CudaTuning::CgForm::Auto;
  cudaStream_t stream_ = nullptr;
  DeviceArray<int4> tets_;
  DeviceArray<T> grad_, vol_, lambda_, mu_, quat_, mass_;
  DeviceArray<int> block_row_, pair_ptr_, pairs_, free_surf_, row_ptr_, col_, free_nodes_, tri_, node_surf_, dof_;
  DeviceArray<T> x_, v_, rec_, vals_, precond_, b_, dv_, dv_prev_, r_, z_, p0_, p1_, q_, ext_[5];
  bool last_converged_ = false;  // the last solve reached the tolerance (warm_start_extrapolates)
  int tight_solves_ = 0;         // count_tight_solves of the last solves
  DeviceArray<T> kept_x_, kept_v_, kept_quat_, kept_dv_, kept_dv_prev_;  // checkpoint()
  std::vector<Eigen::Vector3d> kept_filtered_;
  bool kept_rested_ = true, kept_last_converged_ = false, has_kept_ = false;
  int kept_tight_solves_ = 0;
  DeviceArray<T> reuse_dv_;     // rollback_for_reference(): the undone take's solution
  bool reuse_pending_ = false;  // ... which the next take starts from
  // A take begun (begin_step) and not yet finished: what its end needs.
  enum class Pending { None, Rest, Solve } pending_ = Pending::None;
  std::vector<FingerInput> begun_fingers_;
  bool begun_mg_ = false;
  int slice_ = 0;             // a shadow's solve in slices of this many CG iterations (Beside)
  int slice_mg_ = 0;          // ... with borrowed multigrid levels
  bool borrowed_mg_ = false;  // the levels of the backend it was forked from (fork_reference)
  int slices_launched_ = 0;   // ... launched for the take begun
  int begun_iterations_ = 0;       // the baselines' solve, which returns them at once
  double begun_residual_ = 0;
  cudaEvent_t done_ = nullptr;     // recorded after a take's launches (step_ready) and a fork's copies
  DeviceArray<double> cA_, cb_;
  DeviceArray<DevScratch> scratch_;
  DevResult* host_res_ = nullptr;  // mapped pinned memory
  DevResult* dev_res_ = nullptr;   // its device address
  std::vector<T> rest_;
  DeviceArray<T> rest_dev_;  // the same on the device (the divergence guard's displacement)
  std::vector<Eigen::Vector3d> filtered_;
  bool rested_ = true;
  Profiler prof_;
  PhaseTimes phases_;
  std::unique_ptr<BaselineSolver<T>> baseline_;  // the library baselines' solver
  Materials mat_;                        // the materials set last (an element change rebuilds from them)
  // The nodal-pressure element only (pressure.cuh): its pattern, on the host and the device.
  std::shared_ptr<const NodalPressurePattern> np_;  // none until an element needs it
  std::vector<double> npw_host_;  // its weights W (what the multigrid levels are built from)
  DeviceArray<int> np_row_ptr_, np_col_, np_t_row_ptr_, np_t_node_, np_t_pair_, np_pinc_ptr_, np_pinc_, np_inc_ptr_, np_inc_,
      np_block_pair_, np_fixed_pairs_,
      diag_block_;
  int np_nfixed_ = 0;  // fixed nodes' pairs (np_fixed_pairs_)
  DeviceArray<T> npb_, npw_, npi_, np_rest_part_;
  // The skin membrane (fem_membrane.h, assembly.cuh's skin stage); nskin_ 0: none.
  int nskin_ = 0;
  DeviceArray<int> skin_tri_, skin_row_, skin_base_, skin_stride_, skin_free_;
  DeviceArray<membrane::Rest<T>> skin_rest_;
  // The multigrid preconditioner (Preconditioner::Multigrid*): when its levels are built,
  // their copy on the device, the kernel that runs them and its scratch.
  CudaTuning tuning_;
  MultigridKeeper multigrid_;
  cuda::MultigridDevice mg_levels_;
  // What the levels are built from that does not change with the step (the system's block
  // pattern, copied once since a build may outlive the model; the nodal-pressure pattern,
  // shared with the backend): shared with each build, not copied for it.
  struct LevelsPattern {
    int nf;
    std::vector<int> row_ptr, col;
    std::shared_ptr<const NodalPressurePattern> np;
  };
  std::shared_ptr<const LevelsPattern> levels_pattern_;
  // A device copy of the assembled system for a build to read back on its own thread (the
  // steps go on overwriting vals_ and npb_); kept for the next build once none holds it.
  struct SystemCopy {
    explicit SystemCopy(int device) : device(device) {
      CU(cudaEventCreateWithFlags(&ready, cudaEventDisableTiming));
    }
    SystemCopy(const SystemCopy&) = delete;
    SystemCopy& operator=(const SystemCopy&) = delete;
    ~SystemCopy() { cudaEventDestroy(ready); }
    /// `a` (vals or b) on the host once the copies are done, from any thread.
    std::vector<double> read(const DeviceArray<T>& a) const {
      CU(cudaSetDevice(device));
      CU(cudaEventSynchronize(ready));
      // The legacy default stream: no other work of this backend's goes on it (its stream
      // is non-blocking), and the event above ordered the copies before this read.
      return a.to_host_double(nullptr);
    }
    int device;
    DeviceArray<T> vals, b;
    cudaEvent_t ready = nullptr;
  };
  std::shared_ptr<SystemCopy> system_copy_;
  PcgLaunch mg_launch_;
  DeviceArray<T> mg_r_, mg_d_;
  MultigridCounts multigrid_counts_;
};

}  // namespace

}  // namespace cuda

bool cuda_probe(std::string* why_not) {
  const cuda::DeviceInfo& d = cuda::device_info();
  if (!d.ok && why_not) *why_not = d.why;
  return d.ok;
}

std::unique_ptr<Backend> make_cuda_backend(const Model& model, const SimParams& params) {
  if (params.solver.precision == Precision::Float)
    return std::make_unique<cuda::CudaBackend<float>>(model, params, cuda::Solver::Persistent);
  return std::make_unique<cuda::CudaBackend<double>>(model, params, cuda::Solver::Persistent);
}

std::unique_ptr<Backend> make_cuda_baseline_backend(const std::string& name, const Model& model,
                                                    const SimParams& params) {
#ifndef PALPATION_HAVE_CUSPARSE
  (void)model;
  (void)params;
  throw std::runtime_error("backend " + name + ": this build has no cuSPARSE/cuBLAS");
#else
  cuda::Solver solver;
  if (name == "cuda-csr")
    solver = cuda::Solver::Csr;
  else if (name == "cuda-bsr")
    solver = cuda::Solver::Bsr;
  else
    throw std::runtime_error("backend \"" + name + "\" is not a CUDA baseline (cuda-csr, cuda-bsr)");
  if (params.solver.precision == Precision::Float)
    return std::make_unique<cuda::CudaBackend<float>>(model, params, solver);
  return std::make_unique<cuda::CudaBackend<double>>(model, params, solver);
#endif
}

}  // namespace palpation::sim
