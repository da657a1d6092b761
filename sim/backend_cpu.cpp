// One step (design.md section 4), per time step h:
//   1. per element: F; the rotation R (warm-started) is re-extracted only for elements
//      whose F changed by more than `solver.corotation_tolerance` since the last
//      extraction, and the element's rotated stiffness blocks only when that R moved by
//      more than the tolerance from the one they were built with (below). The rotated
//      stiffness K and b0 = sum_e K_e (R_e - I) X_e are kept from step to step; an update
//      adds the element's new part minus its old one;
//   2. the elastic force minus the stiffness damping, f - (h + beta) K v, as
//      b0 - K (u + (h + beta) v) (u = x - X): one product with the kept K (at tolerance
//      0, element by element, f = -V R sigma(R^T F - I) g, then K v);
//   3. penalty contact on surface triangles inside finger spheres: k_s n n^T and
//      k_e n n^T go to a separate diagonal D with the mass terms;
//   4. solve ((h^2 + h beta) K + D) dv = h (f - (h + beta) K v + ...), D = (1 + h alpha) M
//      + contact, by block-Jacobi preconditioned CG, warm-started from the last dv (the
//      last two extrapolated after tight solves: WarmStart in params.h), over the free
//      nodes only (the chest wall is removed from the system);
//   5. v += dv, x += h v; finger forces re-evaluated at the new state, low-pass filtered.
//
// Skipping the unchanged elements (what a palpation scene does not need): away from
// the fingers the tissue is still and F does not change, so neither do R and the
// blocks. An element keeping a rotation that is off by d theta (at most the tolerance)
// gets a force off by d theta relative and the symmetric part of its strain only to
// second order; between its updates it is exactly a linear element in a fixed frame
// (energy-consistent), which is what makes f = -K u + b0 exact for it. Tolerance 0
// updates every element every step, which is the arithmetic of the CUDA backend (CPU-GPU
// agreement checks use it). docs/benchmarks.md has the measured step time against force
// error.
#include "backend_cpu.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <thread>
#include <utility>

#include <Eigen/Dense>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "contact_sphere.h"
#include "fem_corotational.h"
#include "fem_membrane.h"
#include "multigrid_keeper.h"
#include "lanes4.h"
#include "nodal_pressure.h"
#include "solve_cg.h"

namespace palpation::sim {

std::string cpu_name() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) return line.substr(colon + 2);
    }
  }
  return "CPU";
}

namespace {

// Below this many free nodes a parallel region costs more than it saves (measured:
// see docs/benchmarks.md, "threads").
constexpr int kParallelMinFree = 3000;

// Fewer hardware threads than this: one thread unless asked (solver.threads >= 2). On a
// 2-core machine the other core is the haptic loop's, the GUI's or another job's, and
// OpenMP's spinning barriers then wait on a descheduled thread: paper mesh under load
// 3-4, 96.7 ms median and 1.70 s p99 a step with two threads against 23.5 / 46 ms with one
// (docs/benchmarks.md).
constexpr unsigned kParallelMinCores = 4;

// Full re-assembly of K after this many steps of element-wise updates. Each update adds
// new minus old blocks, so K carries one rounding per update; after 2^16 updates of one
// block that is ~sqrt(65536) x 6e-8 = 1.5e-5 relative in float (2.9e-14 in double), far
// below the CG tolerance. The re-assembly costs one step at the full price (~once a
// minute at 1 kHz).
constexpr long kReassembleSteps = kCpuReassembleSteps;

// Elements per stage of the element pass (CpuBackend::elements).
constexpr int kChunk = 64;

template <class T>
class CpuBackend final : public Backend {
 public:
  using V3 = fem::Vec3<T>;
  using M3 = fem::Mat3<T>;
  using V4 = lanes::V4<T>;

  CpuBackend(const Model& model, const SimParams& params)
      : m_(model), p_(resolved_for(model, params)), given_corotation_(params.solver.corotation_tolerance) {
    const int nn = m_.num_nodes(), ne = m_.num_tets(), nf = m_.num_free();
    x_.resize(3 * nn + 1);  // + 1: four-lane loads of the last node (element())
    v_.resize(3 * nn);
    q_.resize(ne);
    ekrot_.resize(9 * std::size_t(ne));
    eF_.resize(12 * std::size_t(ne));
    // Extra blocks and rows at the end (one per thread) take the contributions of fixed
    // nodes, so that the element loop has no branches (see element()).
#ifdef _OPENMP
    threads_ = std::max(1, omp_get_max_threads());
#endif
    blocks_.resize(9 * (std::size_t(m_.num_blocks()) + threads_));
    diag_.resize(9 * std::size_t(nf) + 1);  // + 1: cg::multiply reads one past a block
    b_.resize(3 * (std::size_t(nf) + threads_));
    b0_.resize(3 * (std::size_t(nf) + threads_));
    dv_.resize(3 * nf);
    kv_.resize(3 * nf);
    vfree_.resize(3 * nf + 1);  // + 1: a product through the upper triangle reads one past (cg::UpperBlocks)
    build_upper_pattern();
    build_element_tables();
    build_skin_tables();
    cg_.resize(3 * nf);
    cg_.precond_kept = true;  // refresh_preconditioner() keeps cg_.precond
    pc_dirty_.assign(std::size_t(nf), 1);
    set_materials(m_.materials);
    reset();
  }

  std::string name() const override { return "cpu"; }
  std::string device_name() const override { return cpu_name(); }
  Precision precision() const override {
    return std::is_same_v<T, double> ? Precision::Double : Precision::Float;
  }
  const SimParams& params() const override { return p_; }
  void set_params(const SimParams& given) override {
    // A corotation tolerance read back from params() (resolved from the force-error
    // target) and passed again stands for the one first given: a later change of the
    // target (to 0: fixed) resolves from that, not from the target it replaced.
    SimParams g = given;
    if (g.solver.corotation_tolerance == p_.solver.corotation_tolerance) g.solver.corotation_tolerance = given_corotation_;
    given_corotation_ = g.solver.corotation_tolerance;
    const SimParams p = resolved_for(m_, g);
    // The kept K and b0 belong to the tolerance they were built under: at 0 b0 is not
    // kept at all, so a switch to above 0 would lose every still element's rotation term
    // until the next full assembly. Any change of tolerance assembles afresh.
    if (p.solver.corotation_tolerance != p_.solver.corotation_tolerance) assembled_ = false;
    const bool element_changed = p.element != p_.element;
    if (p.solver.preconditioner != p_.solver.preconditioner) multigrid_.invalidate();
    // A body at rest is at rest under the parameters it settled with: a new gravity (or
    // anything else but dt and threads) is solved for.
    if (differ_beyond_step(p, p_)) rested_ = false;
    p_ = p;
    if (element_changed) set_materials(mat_);
  }
  const CpuWorkCounters& counters() const { return counters_; }
  double preconditioner_staleness() const {
    if (pc_scale_ < 0) return -1;  // nothing solved yet
    const cg::BlockSystem<T> sys = system(T(p_.solver.dt));
    std::vector<T> fresh(cg_.precond.size());
    cg::build_block_jacobi(sys, fresh.data());
    double d = 0;
    for (std::size_t k = 0; k < fresh.size(); ++k) d = std::max(d, double(std::abs(fresh[k] - cg_.precond[k])));
    return d;
  }
  MultigridCounts multigrid_counts() const override { return multigrid_.with_smoother(multigrid_counts_); }
  void prepare_solver() override {
    if (!is_multigrid(p_.solver.preconditioner) || !rested_) return;
    const T h = T(p_.solver.dt);
    assemble(h);  // the rest state's blocks: the first step after it finds them assembled
    use_multigrid(system(h), false);
  }
  void set_deferred_levels(bool on) override { multigrid_.set_deferred(on); }
  std::shared_ptr<LevelsJob> take_levels_job() override { return multigrid_.take_job(); }
  bool install_levels(const std::shared_ptr<LevelsJob>& job) override {
    return multigrid_.install(job, [](const amg::Hierarchy&) {}, multigrid_counts_.builds, multigrid_counts_.failures);
  }

  // The element caches (F, the rotations q_, K blocks) need no copy while elements are
  // kept (corotation_tolerance > 0): they are formed from the start-of-step positions, and
  // a step taken again from the same positions finds them as its first take left them,
  // which is what it would have made of them itself. At tolerance 0 every element is
  // extracted again each take, warm-started from q_, so q_ is kept too.
  bool checkpoint() override {
    kept_.valid = true;
    kept_.q.clear();
    if (p_.solver.corotation_tolerance == 0) kept_.q = q_;
    kept_.x = x_;
    kept_.v = v_;
    kept_.dv = dv_;
    kept_.dvprev = dvprev_;
    kept_.filtered = filtered_;
    kept_.rested = rested_;
    kept_.last_converged = last_converged_;
    kept_.tight_solves = tight_solves_;
    return true;
  }
  void rollback() override {
    if (!kept_.valid) return;
    if (kept_.q.size() == q_.size()) q_ = kept_.q;
    x_ = kept_.x;
    v_ = kept_.v;
    dv_ = kept_.dv;
    dvprev_ = kept_.dvprev;
    filtered_ = kept_.filtered;
    rested_ = kept_.rested;
    last_converged_ = kept_.last_converged;
    tight_solves_ = kept_.tight_solves;
  }
  void rollback_for_reference() override {
    if (!kept_.valid) return;
    reuse_dv_.swap(dv_);  // the undone take's solution (dv_ is restored below)
    rollback();
    reuse_pending_ = true;
  }

  // Only where every element is extracted in every take (corotation tolerance 0): kept
  // element caches are formed by a backend's own history, which a shadow does not share, and
  // a check against a shadow that extracts them all would measure the kept rotations' error
  // (about 1e-4 of the force, docs/benchmarks.md), not the solve's: the controller could
  // then never loosen.
  std::unique_ptr<Backend> make_shadow(const SimParams& params) const override {
    if (params.solver.check == CheckPlace::Auto) return nullptr;  // the in-step check costs no more here
    if (p_.solver.corotation_tolerance > 0 || params.solver.corotation_tolerance > 0) return nullptr;
    auto s = std::make_unique<CpuBackend<T>>(m_, params);
    s->set_materials(mat_);
    return s;
  }
  bool fork_reference(Backend& shadow) override {
    auto* s = dynamic_cast<CpuBackend<T>*>(&shadow);
    if (!s || s == this || &s->m_ != &m_ || !kept_.valid) return false;
    s->q_ = kept_.q.size() == q_.size() ? kept_.q : q_;  // a warm start of the polar decompositions
    s->x_ = kept_.x;
    s->v_ = kept_.v;
    s->dv_ = kept_.dv;
    s->dvprev_ = kept_.dvprev;
    s->filtered_ = kept_.filtered;
    s->rested_ = kept_.rested;
    s->last_converged_ = kept_.last_converged;
    s->tight_solves_ = kept_.tight_solves;
    s->reuse_dv_ = dv_;
    s->reuse_pending_ = true;
    s->kept_.valid = false;
    return true;
  }

  void set_materials(const Materials& mat) override {
    const int ne = m_.num_tets();
    if (&mat != &mat_) mat_ = mat;
    multigrid_.invalidate();  // another system: the multigrid levels are built again
    lambda_.resize(ne);
    mu_.resize(ne);
    // The nodal-pressure element takes lambda out of the element blocks into its nodal term.
    const bool nodal = p_.element == Element::NodalPressure;
    for (int e = 0; e < ne; ++e) {
      lambda_[e] = nodal ? T(0) : T(mat.lambda[e]);
      mu_[e] = T(mat.mu[e]);
    }
    if (nodal) build_nodal_pressure(mat);
    rested_ = false;
    assembled_ = false;  // every element's blocks change: assemble K afresh
  }

  // Per-element constants in T, contiguous, read once per element per step: shape
  // gradients, volume, g_a . g_b (a <= b), and the offsets of each of the 16 blocks and
  // 4 rows (-1 for a fixed node: element() sends those to its thread's trash slot).
  void build_element_tables() {
    const int ne = m_.num_tets();
    eg_.resize(12 * std::size_t(ne));
    eX_.resize(12 * std::size_t(ne));
    egg_.resize(10 * std::size_t(ne));
    evol_.resize(ne);
    eblk_.resize(16 * std::size_t(ne));
    eup_.resize(16 * std::size_t(ne));
    erow_.resize(4 * std::size_t(ne));
    for (int e = 0; e < ne; ++e) {
      evol_[e] = T(m_.volume[e]);
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      for (int a = 0; a < 4; ++a) c += 0.25 * m_.rest[m_.tets[e][a]];
      for (int a = 0; a < 4; ++a)
        for (int k = 0; k < 3; ++k) eX_[12 * std::size_t(e) + 3 * a + k] = T(m_.rest[m_.tets[e][a]][k] - c[k]);
      for (int a = 0; a < 4; ++a) {
        for (int k = 0; k < 3; ++k) eg_[12 * std::size_t(e) + 3 * a + k] = T(m_.grad[e][a][k]);
        const int row = m_.dof[m_.tets[e][a]];
        erow_[4 * std::size_t(e) + a] = row < 0 ? -1 : 3 * row;
      }
      int pair = 0;
      for (int a = 0; a < 4; ++a)
        for (int b = a; b < 4; ++b) egg_[10 * std::size_t(e) + pair++] = T(m_.grad[e][a].dot(m_.grad[e][b]));
      for (int k = 0; k < 16; ++k) {
        const int blk = m_.tet_block[e][k];
        eblk_[16 * std::size_t(e) + k] = blk < 0 ? -1 : 9 * blk;
        eup_[16 * std::size_t(e) + k] = blk < 0 ? -1 : up_of_block_[std::size_t(blk)];
      }
    }
  }

  // The upper triangle of the block pattern (cg::UpperBlocks: row i's columns c >= i, the
  // diagonal first since each row's columns ascend), each full block's entry in it (that of
  // its pair of rows in either order), and its arrays, kept beside the full ones: where a
  // full block (r, c) with r >= c changes, so does upper entry (c, r), which holds A_rc;
  // where the couplings at a block (r, c) with r <= c do, so do entry (r, c)'s.
  void build_upper_pattern() {
    const int nf = m_.num_free();
    up_row_ptr_.assign(std::size_t(nf) + 1, 0);
    up_col_.clear();
    up_of_block_.assign(std::size_t(m_.num_blocks()), -1);
    for (int i = 0; i < nf; ++i) {
      for (int k = m_.row_ptr[i]; k < m_.row_ptr[i + 1]; ++k) {
        const int c = m_.col[k];
        if (c < i) continue;
        const int u = static_cast<int>(up_col_.size());
        up_col_.push_back(c);
        up_of_block_[std::size_t(k)] = u;
        up_of_block_[std::size_t(m_.block_of(c, i))] = u;
      }
      up_row_ptr_[std::size_t(i) + 1] = static_cast<int>(up_col_.size());
    }
    const std::size_t nu = up_col_.size();
    ublocks_.assign(9 * nu + 1, T(0));  // + 1: four-lane loads of the last block
    uscatter_.assign(4 * std::size_t(nf), T(0));
    upper_ = cg::UpperBlocks<T>{up_row_ptr_.data(), up_col_.data(), ublocks_.data(), nullptr, nullptr, uscatter_.data()};
  }

  // The skin membrane's rest data in T and room for what each triangle last added.
  void build_skin_tables() {
    const auto& sk = m_.skin;
    skin_rest_.resize(std::size_t(sk.size()));
    for (int t = 0; t < sk.size(); ++t) skin_rest_[std::size_t(t)] = membrane::rest_cast<T>(sk.rest[std::size_t(t)]);
    skin_k_.assign(81 * std::size_t(sk.size()), T(0));
    skin_b0_.assign(9 * std::size_t(sk.size()), T(0));
  }

  // The skin membrane (fem_membrane.h), every triangle every step and serially: a surface
  // has a few thousand triangles against tens of thousands of elements, and each is cheap.
  // With the kept K (tolerance > 0) a triangle adds its blocks and its part of b0 as new
  // minus what it last added; its part of b0 is f + K u, so that -K u + b0 is its force now
  // and -K (u + du) + b0 = f - K du its linearisation about the present positions.
  // At tolerance 0 (or a full assembly) its blocks go in afresh, and at tolerance 0 its
  // force straight into b_, as the elements' do.
  void skin(bool full, bool kept) {
    const auto& sk = m_.skin;
    if (sk.empty()) return;
    const T lp = T(sk.lambda_plane()), mu = T(sk.mu());
    for (int t = 0; t < sk.size(); ++t) {
      const std::size_t ts = std::size_t(t);
      const auto& tri = sk.triangles[ts];
      T x[9], u[9];
      for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c) {
          x[3 * a + c] = x_[3 * std::size_t(tri[a]) + c];
          u[3 * a + c] = x[3 * a + c] - T(m_.rest[std::size_t(tri[a])][c]);
        }
      T f[9], K[81];
      membrane::element(skin_rest_[ts], x, lp, mu, f, K);
      T* last_k = &skin_k_[81 * ts];
      T* last_b = &skin_b0_[9 * ts];
      const bool increment = kept && !full;
      for (int ab = 0; ab < 9; ++ab) {
        const int blk = sk.block[ts][std::size_t(ab)];
        if (blk < 0) continue;
        T* dst = &blocks_[9 * std::size_t(blk)];  // column-major
        // Block (row of a, row of b) is also the upper entry's when its row is the larger.
        const int ra = m_.dof[std::size_t(tri[ab / 3])], rb = m_.dof[std::size_t(tri[ab % 3])];
        T* up = ra >= rb ? &ublocks_[9 * std::size_t(up_of_block_[std::size_t(blk)])] : nullptr;
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) {
            const T d = K[9 * ab + 3 * i + j] - (increment ? last_k[9 * ab + 3 * i + j] : T(0));
            dst[3 * j + i] += d;
            if (up) up[3 * j + i] += d;
          }
      }
      std::copy(K, K + 81, last_k);
      for (int a = 0; a < 3; ++a) {
        const int row = m_.dof[std::size_t(tri[a])];
        if (row >= 0) pc_dirty_[std::size_t(row)] = 1;  // its diagonal block changed
        T part[3];
        for (int i = 0; i < 3; ++i) {
          part[i] = f[3 * a + i];
          if (kept)
            for (int b = 0; b < 3; ++b)
              for (int j = 0; j < 3; ++j) part[i] += K[9 * (3 * a + b) + 3 * i + j] * u[3 * b + j];
        }
        if (row >= 0) {
          T* dst = kept ? &b0_[3 * std::size_t(row)] : &b_[3 * std::size_t(row)];
          for (int i = 0; i < 3; ++i) dst[i] += part[i] - (increment ? last_b[3 * a + i] : T(0));
        }
        for (int i = 0; i < 3; ++i) last_b[3 * a + i] = part[i];
      }
    }
  }

  // The nodal-pressure term's pattern (once), its weights for these materials, and the
  // per-element pair offsets (-1 for a fixed node: element() skips those).
  void build_nodal_pressure(const Materials& mat) {
    const int ne = m_.num_tets(), nn = m_.num_nodes(), nf = m_.num_free();
    if (np_.row_ptr.empty()) {
      np_ = build_nodal_pressure_pattern(m_);
      npb_.assign(3 * std::size_t(np_.num_pairs()), T(0));
      epair_.resize(16 * std::size_t(ne));
      for (int e = 0; e < ne; ++e)
        for (int k = 0; k < 16; ++k) epair_[16 * std::size_t(e) + k] = np_.tet_pair[e][k];
      // The couplings in the block order as well, kept beside npb_ by rotate_pairs (with
      // the blocks' trash slots for fixed rows), for the CG's product by block rows.
      npbb_.assign(3 * (std::size_t(m_.num_blocks()) + threads_) + 1, T(0));
      npbt_.assign(npbb_.size(), T(0));
      ubb_.assign(3 * up_col_.size() + 1, T(0));
      ubt_.assign(ubb_.size(), T(0));
      upper_.bb = ubb_.data();
      upper_.bt = ubt_.data();
      npi_.resize(nn);
      npif_.resize(nf);
      npc_.resize(nn);
      npx_.assign(3 * std::size_t(nf) + 1, T(0));  // + 1: the padded pass's four-lane loads
      npdiag_.resize(9 * std::size_t(nf));
    }
    const std::vector<double> w = nodal_pressure_weights(m_, np_, mat.lambda);
    npw_.assign(w.begin(), w.end());
    npt_ = cg::PressureTerm<T>{nn, np_.row_ptr.data(), np_.col.data(), np_.t_row_ptr.data(), np_.t_node.data(),
                               np_.t_pair.data(), npb_.data(), npw_.data(), npi_.data()};
    cg::set_block_layout(npt_, np_, m_.free_nodes.data(), npbb_.data(), npbt_.data(), npif_.data());
  }

  void reset() override {
    for (int i = 0; i < m_.num_nodes(); ++i)
      for (int k = 0; k < 3; ++k) x_[3 * i + k] = T(m_.rest[i][k]);
    std::fill(v_.begin(), v_.end(), T(0));
    std::fill(dv_.begin(), dv_.end(), T(0));
    dvprev_.clear();
    last_converged_ = false;
    tight_solves_ = 0;
    multigrid_.invalidate();
    kept_.valid = false;
    reuse_pending_ = false;
    for (auto& q : q_) q.setIdentity();
    filtered_.clear();
    rested_ = p_.gravity.squaredNorm() == 0;
    assembled_ = false;
  }

  void positions(std::vector<double>& xyz) const override { xyz.assign(x_.begin(), x_.begin() + 3 * m_.num_nodes()); }
  void velocities(std::vector<double>& xyz) const override { xyz.assign(v_.begin(), v_.end()); }

  StepStats step(std::span<const FingerInput> fingers, std::span<FingerOutput> out) override {
    StepStats st;
    const bool reuse = std::exchange(reuse_pending_, false);  // rollback_for_reference() just before
    const T h = T(p_.solver.dt);
    const int nf = m_.num_free();
    if (filtered_.size() != fingers.size()) filtered_.assign(fingers.size(), Eigen::Vector3d::Zero());

    // Contact detection at the start-of-step positions against end-of-step fingers.
    surface_bounds();
    contact::detect<T>(fingers, m_.surface, x_.data(), bounds_, contacts_);
    st.contacts = static_cast<int>(contacts_.size());

    ++counters_.steps;
    // Skip what the scene does not need: no contact and at rest -> no solve.
    if (contacts_.empty() && rested_) {
      ++counters_.skipped_at_rest;
      finger_outputs(fingers, out);
      return st;
    }

    if (parallel()) ++counters_.parallel_steps;
    assemble(h);
    add_gravity_and_damping_rhs(h);
    add_contacts(fingers, h);

    const cg::BlockSystem<T> sys = system(h);
    // Warm start (WarmStart in params.h): the last two solutions extrapolated linearly
    // (the velocity change of a pushed body varies smoothly from step to step; at CG 1e-3
    // 10-13 % fewer CG iterations than the last solution alone), or the last solution.
    // Extrapolated only after a converged solve (WarmStart::Last: two tight ones): with the
    // iterations capped below convergence, extrapolating the truncation error doubles it
    // every step (the capped bench settings diverged), and so it does a loose solve's. A
    // guess far worse than zero is caught by cg::solve, which then starts from zero.
    if (reuse && reuse_dv_.size() == dv_.size()) {
      // rollback_for_reference(): from the undone take's solution; the previous step's
      // solution is kept for the next extrapolation, as an extrapolating take keeps it.
      dvprev_ = dv_;
      dv_.swap(reuse_dv_);
    } else if (dvprev_.size() == dv_.size() && warm_start_extrapolates(p_.solver.warm_start, last_converged_, tight_solves_)) {
      for (std::size_t i = 0; i < dv_.size(); ++i) {
        const T cur = dv_[i];
        dv_[i] = T(2) * cur - dvprev_[i];
        dvprev_[i] = cur;
      }
    } else {
      dvprev_ = dv_;
    }
    refresh_preconditioner(sys);
    use_multigrid(sys);
    const auto res = cg::solve(sys, b_.data(), dv_.data(), T(p_.solver.cg_tolerance), p_.solver.cg_max_iterations,
                               cg_, parallel(), T(p_.solver.cg_rescue_tolerance), p_.solver.cg_rescue_iterations);
    st.cg_iterations = res.iterations;
    st.rescued = res.rescued;
    // A capped solve that stops short of its tolerance but within the rescue tolerance is
    // what the cap asked for; one beyond both (or not finite) says the levels no longer fit.
    if (cg_.multigrid)
      note_multigrid_iterations(res.iterations, res.relative_residual <= std::max(p_.solver.cg_tolerance,
                                                                                  p_.solver.cg_rescue_tolerance));
    last_converged_ = res.converged;
    tight_solves_ = count_tight_solves(tight_solves_, res.relative_residual);
    st.cg_residual = res.relative_residual;
    st.solved = true;

    T vmax = 0, dvmax = 0;
    double v2max = 0, d2max = 0, ke = 0;
    for (int i = 0; i < nf; ++i) {
      const int node = m_.free_nodes[i];
      double v2 = 0, d2 = 0;
      for (int k = 0; k < 3; ++k) {
        T& v = v_[3 * node + k];
        v += dv_[3 * i + k];
        x_[3 * node + k] += h * v;
        vmax = std::max(vmax, std::abs(v));
        dvmax = std::max(dvmax, std::abs(dv_[3 * i + k]));
        v2 += double(v) * double(v);
        const double d = double(x_[3 * node + k]) - m_.rest[node][k];
        d2 += d * d;
      }
      v2max = std::max(v2max, v2);
      d2max = std::max(d2max, d2);
      ke += 0.5 * m_.mass[node] * v2;
    }
    st.finite = std::isfinite(double(vmax)) && std::isfinite(double(res.relative_residual));
    // At rest: no contact, velocities and their change negligible (1 um/s).
    if (contacts_.empty() && vmax < T(1e-6) && dvmax < T(1e-7)) {
      std::fill(v_.begin(), v_.end(), T(0));
      rested_ = true;
      v2max = ke = 0;
    } else {
      rested_ = false;
    }
    const bool finite_v = std::isfinite(double(vmax)) && std::isfinite(ke);
    st.max_speed = finite_v ? std::sqrt(v2max) : INFINITY;
    st.max_displacement = finite_v && std::isfinite(d2max) ? std::sqrt(d2max) : INFINITY;
    st.kinetic_energy = finite_v ? ke : INFINITY;
    finger_outputs(fingers, out);
    for (const auto& o : out) st.finite = st.finite && o.force.allFinite();
    return st;
  }

 private:
  bool nodal() const { return p_.element == Element::NodalPressure; }
  // The mass terms' factor on the diagonal, 1 + h alpha.
  T mass_scale() const { return T(1) + T(p_.solver.dt) * T(p_.damping.mass); }

  // The step's system as assembled: (h^2 + h beta) K + D, and the nodal-pressure term.
  cg::BlockSystem<T> system(T h) const {
    cg::BlockSystem<T> sys{m_.num_free(), m_.row_ptr.data(), m_.col.data(), blocks_.data()};
    sys.scale = h * h + h * T(p_.damping.stiffness);
    sys.diag = diag_.data();
    sys.diag_index = m_.diag_block.data();
    sys.upper = &upper_;
    if (nodal()) {
      sys.pressure = &npt_;
      sys.pressure_diag = npdiag_.data();
    }
    return sys;
  }

  // The block-Jacobi inverses (cg_.precond) for this step's system, kept from the last: only
  // the rows whose diagonal block changed are inverted again, those marked in pc_dirty_
  // (the rows of re-rotated elements, of the skin's triangles and of contacts, now or in the
  // last solved system), or all of them after a full assembly or where the time step or
  // the mass damping changed the scales. On the paper breast most rows are still: inverting
  // all of them every step cost a product's worth.
  void refresh_preconditioner(const cg::BlockSystem<T>& sys) {
    const int nf = m_.num_free();
    const T mscale = mass_scale();
    const bool all = pc_all_ || sys.scale != pc_scale_ || mscale != pc_mscale_;
    for (int i = 0; i < nf; ++i) {
      if (!all && !pc_dirty_[std::size_t(i)]) continue;
      cg::invert_diagonal(sys, i, cg_.precond.data());
      pc_dirty_[std::size_t(i)] = 0;
      ++counters_.preconditioner_rows;
    }
    pc_all_ = false;
    pc_scale_ = sys.scale;
    pc_mscale_ = mscale;
  }

  // The levels below this step's system, when the preconditioner is a multigrid and they
  // are due (multigrid_keeper.h).
  void use_multigrid(const cg::BlockSystem<T>& sys, bool may_defer = true) {
    const bool use = multigrid_.prepare(
        p_.solver.preconditioner, double(sys.scale), m_,
        [&]() -> LevelsSystem {
          // Converted here, in the step (a few ms on the paper mesh): the blocks change with it.
          auto stiffness = std::make_shared<const amg::SpMat>(cg::to_sparse(sys));
          auto pressure = std::make_shared<const amg::SpMat>(sys.pressure ? cg::pressure_to_sparse(sys) : amg::SpMat());
          return [stiffness, pressure](amg::SpMat& k, amg::SpMat& np) {
            k = *stiffness;
            np = *pressure;
          };
        },
        [](const amg::Hierarchy&) {}, multigrid_counts_.builds, multigrid_counts_.failures, may_defer);
    cg_.multigrid = use ? &multigrid_.levels() : nullptr;
  }
  void note_multigrid_iterations(int iterations, bool solved) { multigrid_.note(iterations, solved, p_.solver.cg_tolerance); }

  // threads: 1 = serial, >= 2 = always parallel (OpenMP's team), 0 = where it pays; and
  // never with a team of one (OMP_NUM_THREADS=1): the parallel passes would run on it in
  // colour order, which scatters the element arrays (paper breast: 1.23x a step).
  bool parallel() const {
    if (threads_ < 2) return false;
    return p_.solver.threads >= 2 || (p_.solver.threads == 0 && m_.num_free() >= kParallelMinFree && cores_ >= kParallelMinCores);
  }

  void surface_bounds() {
    contact::Bounds b;
    for (int node : m_.surface_nodes)
      for (int k = 0; k < 3; ++k) {
        b.lo[k] = std::min(b.lo[k], double(x_[3 * node + k]));
        b.hi[k] = std::max(b.hi[k], double(x_[3 * node + k]));
      }
    bounds_ = b;
  }

  // The rotated stiffness K (unscaled) kept in blocks_, updated element by element; into
  // b_ the elastic force minus the stiffness damping, f - (beta + h) K v; mass terms into
  // diag_.
  //
  // With a kept rotation R an element is exactly linear: f_a = -sum_b K_ab(R) (x_b - R X_b)
  // = -sum_b K_ab u_b + sum_b K_ab (R - I) X_b (u = x - X, X the rest positions; the
  // chest wall's u is 0). So with every element at the rotation its blocks were built
  // with, f = -K u + b0, b0 = sum over elements of K_e (R_e - I) X_e, kept like K (an
  // element's update adds its new minus its old part), and f - (beta + h) K v is one
  // product: b0 - K (u + (beta + h) v). The element pass then only computes F and checks
  // it; the per-element force (R sigma(R^T F - I) g) is formed only at tolerance 0, the
  // CUDA backend's arithmetic, where every element is re-rotated every step anyway.
  void assemble(T h) {
    // Assembled in full at the start, after a reset or a material change, and every
    // kReassembleSteps updates (the increments' rounding stays far below the CG
    // tolerance even in float; see kReassembleSteps).
    // Tolerance 0 (every element every step) assembles afresh rather than adding
    // new-minus-old blocks (half the block work).
    const T tol = T(p_.solver.corotation_tolerance);
    const bool kept = tol > 0;
    const bool full = !assembled_ || !kept || steps_since_assembly_ >= kReassembleSteps;
    if (full) {
      std::fill(blocks_.begin(), blocks_.end(), T(0));
      std::fill(b0_.begin(), b0_.end(), T(0));
      std::fill(npb_.begin(), npb_.end(), T(0));
      std::fill(npbb_.begin(), npbb_.end(), T(0));
      std::fill(npbt_.begin(), npbt_.end(), T(0));
      std::fill(ublocks_.begin(), ublocks_.end(), T(0));
      std::fill(ubb_.begin(), ubb_.end(), T(0));
      std::fill(ubt_.begin(), ubt_.end(), T(0));
      steps_since_assembly_ = 0;
      ++counters_.full_assemblies;
      pc_all_ = true;
    }
    ++steps_since_assembly_;
    if (!kept) std::fill(b_.begin(), b_.end(), T(0));
    const bool par = parallel();
    if (par) {
      // Colour by colour: no two elements of a colour share a node, so threads never add
      // to the same block or row.
      for (const auto& colour : m_.colours) {
        const int count = static_cast<int>(colour.size());
        const int chunks = (count + kChunk - 1) / kChunk;
#pragma omp parallel for schedule(static)
        for (int k = 0; k < chunks; ++k)
          elements(std::min(kChunk, count - k * kChunk), [&](int c) { return colour[k * kChunk + c]; }, full, kept, tol);
      }
    } else {
      // One thread: in storage order, so the per-element arrays stream through the cache
      // (the colours scatter them).
      for (int e0 = 0; e0 < m_.num_tets(); e0 += kChunk)
        elements(std::min(kChunk, m_.num_tets() - e0), [e0](int c) { return e0 + c; }, full, kept, tol);
    }
    skin(full, kept);
    assembled_ = true;
    const int nf = m_.num_free();
    const T damp = T(p_.damping.stiffness) + h;
    cg::BlockSystem<T> K{nf, m_.row_ptr.data(), m_.col.data(), blocks_.data()};
    K.upper = &upper_;
    if (kept) {
      for (int i = 0; i < nf; ++i) {
        const int node = m_.free_nodes[i];
        for (int k = 0; k < 3; ++k)
          vfree_[3 * i + k] = x_[3 * node + k] - T(m_.rest[node][k]) + damp * v_[3 * node + k];
      }
      cg::multiply(K, vfree_.data(), kv_.data(), par);
      for (int i = 0; i < 3 * nf; ++i) b_[i] = b0_[i] - kv_[i];
    } else {
      // K v over the free nodes (the chest wall does not move).
      for (int i = 0; i < nf; ++i)
        for (int k = 0; k < 3; ++k) vfree_[3 * i + k] = v_[3 * m_.free_nodes[i] + k];
      cg::multiply(K, vfree_.data(), kv_.data(), par);
      for (int i = 0; i < 3 * nf; ++i) b_[i] -= damp * kv_[i];
    }
    if (nodal()) nodal_pressure_forces(damp, par);
    // Mass terms of the diagonal: (1 + h alpha) M.
    const T mscale = mass_scale();
    std::fill(diag_.begin(), diag_.end(), T(0));
    for (int i = 0; i < nf; ++i) {
      T* d = &diag_[9 * std::size_t(i)];
      const T mm = mscale * T(m_.mass[m_.free_nodes[i]]);
      d[0] = d[4] = d[8] = mm;
    }
  }

  // K_ab = V (lambda r_a r_b^T + mu r_b r_a^T + mu (g_a . g_b) I) for r_a = R g_a, without
  // its identity part, by columns: column j of K_ab is lambda r_a (r_b)_j + mu r_b (r_a)_j,
  // column j of K_ba = K_ab^T is lambda (r_a)_j r_b + mu (r_b)_j r_a (lra = V lambda r_a,
  // mra = V mu r_a).
  static void block_pair(V4 lra, V4 mra, V4 rb, V4 kc[3], V4 kr[3]) {
    for (int j = 0; j < 3; ++j) {
      kc[j] = lra * rb[j] + rb * mra[j];
      kr[j] = rb * lra[j] + mra * rb[j];
    }
  }

  // Adds an element's rotated stiffness blocks for r1 (r_a = R g_a) to blocks_, minus
  // those for r0 when r0 is given (a re-rotation: the identity parts cancel), and when y1
  // is given (y_b = (R - I) X_b) its part of b0, sum_b K_ab y_b, to b0_ at rows[a], minus
  // the old part for r0, y0. Symmetric: K_ba = K_ab^T, so 10 of the 16 blocks are computed.
  void rotate_blocks(std::size_t e, const V4 r1[4], const V4* y1, const V4* r0, const V4* y0, const int blk[16],
                     const int rows[4]) {
    const T* gg = &egg_[10 * e];
    const T la = evol_[e] * lambda_[e], mb = evol_[e] * mu_[e];
    V4 acc[4] = {};  // b0 rows
    int pair = 0;
    for (int a = 0; a < 4; ++a) {
      const V4 lra1 = la * r1[a], mra1 = mb * r1[a];
      V4 lra0 = {}, mra0 = {};
      if (r0) {
        lra0 = la * r0[a];
        mra0 = mb * r0[a];
      }
      for (int b = a; b < 4; ++b) {
        const T mg = mb * gg[pair++];
        V4 kc[3], kr[3];
        block_pair(lra1, mra1, r1[b], kc, kr);
        if (r0) {
          V4 kc0[3], kr0[3];
          block_pair(lra0, mra0, r0[b], kc0, kr0);
          if (y1) {
            acc[a] += lanes::mul<T>(kc, y1[b]) - lanes::mul<T>(kc0, y0[b]) + mg * (y1[b] - y0[b]);
            if (b != a) acc[b] += lanes::mul<T>(kr, y1[a]) - lanes::mul<T>(kr0, y0[a]) + mg * (y1[a] - y0[a]);
          }
          for (int j = 0; j < 3; ++j) {
            kc[j] -= kc0[j];
            kr[j] -= kr0[j];
          }
        } else {
          for (int j = 0; j < 3; ++j) {
            kc[j][j] += mg;
            kr[j][j] += mg;
          }
          if (y1) {
            acc[a] += lanes::mul<T>(kc, y1[b]);
            if (b != a) acc[b] += lanes::mul<T>(kr, y1[a]);
          }
        }
        lanes::add_block<T>(&blocks_[std::size_t(blk[4 * a + b])], kc);
        if (b != a) lanes::add_block<T>(&blocks_[std::size_t(blk[4 * b + a])], kr);
        // The upper entry of the pair holds the block whose row is the larger one.
        if (const int u = eup_[16 * e + 4 * a + b]; u >= 0) lanes::add_block<T>(&ublocks_[9 * std::size_t(u)], rows[a] >= rows[b] ? kc : kr);
      }
    }
    if (!y1) return;
    for (int a = 0; a < 4; ++a) {
      T* bb = &b0_[std::size_t(rows[a])];
      for (int k = 0; k < 3; ++k) bb[k] += acc[a][k];
    }
  }

  // The element's part of the nodal-pressure couplings b_nj, (V / 4) r_j for each of its
  // nodes n and free nodes j, for r1 (r_j = R g_j), minus that for r0 when given; into
  // npb_ (pair order) and npbb_ / npbt_ (block order: pair (n, j) is the element's block
  // (n, j), and its transpose (j, n); a fixed n's go to the trash slot). A pair (n, j)
  // belongs to elements that hold the free node j, which no two elements of one colour
  // share: race-free under the coloured parallel pass.
  void rotate_pairs(std::size_t e, const V4 r1[4], const V4* r0, const int blk[16]) {
    const T q = T(0.25) * evol_[e];
    const int* pr = &epair_[16 * e];
    for (int b = 0; b < 4; ++b) {
      const V4 d = q * (r0 ? r1[b] - r0[b] : r1[b]);
      for (int a = 0; a < 4; ++a) {
        const int k = pr[4 * a + b];
        if (k < 0) continue;
        T* bk = &npb_[3 * std::size_t(k)];
        T* bb = &npbb_[std::size_t(blk[4 * a + b] / 3)];  // blk: 9 T a block, here 3
        T* bt = &npbt_[std::size_t(blk[4 * b + a] / 3)];
        for (int c = 0; c < 3; ++c) {
          bk[c] += d[c];
          bb[c] += d[c];
          bt[c] += d[c];
        }
        // The upper entry (min, max) of the rows: bb where n's row is the smaller, bt where
        // it is the larger (both on the diagonal). A fixed n has none.
        if (const int u = eup_[16 * e + 4 * a + b]; u >= 0) {
          const int ra = erow_[4 * e + a], rb = erow_[4 * e + b];
          for (int c = 0; c < 3; ++c) {
            if (ra <= rb) ubb_[3 * std::size_t(u) + c] += d[c];
            if (ra >= rb) ubt_[3 * std::size_t(u) + c] += d[c];
          }
        }
      }
    }
  }

  // The nodal-pressure term's part of b_ (the elastic force minus its stiffness damping,
  // as for the blocks in assemble()): -B^T W (B (u + damp v) + c), where
  // c_n = sum_{e at n} (V_e / 4) (tr R_e - 3) is B's rest-position part (sum_j b_nj . X_j,
  // since sum_a (R g_a) . X_a = tr R for the element's rotation R); and the diagonal
  // blocks of B^T W B for the preconditioner.
  void nodal_pressure_forces(T damp, bool par) {
    const int nf = m_.num_free(), ne = m_.num_tets();
    std::fill(npc_.begin(), npc_.end(), T(0));
    for (int e = 0; e < ne; ++e) {
      const T* Rk = &ekrot_[9 * std::size_t(e)];
      const T ce = T(0.25) * evol_[e] * ((Rk[0] + Rk[4] + Rk[8]) - T(3));
      for (int a = 0; a < 4; ++a) npc_[m_.tets[e][a]] += ce;
    }
    for (int i = 0; i < nf; ++i) {
      const int node = m_.free_nodes[i];
      for (int k = 0; k < 3; ++k)
        npx_[3 * i + k] = x_[3 * node + k] - T(m_.rest[node][k]) + damp * v_[3 * node + k];
    }
    // By block rows, as the CG's products (solve_cg.h): the diagonal block of row j,
    // sum_n w_n b_nj b_nj^T, from bt along the row (b_{n(c) j} at block (j, c)) and the
    // row's pairs with fixed nodes.
    cg::BlockSystem<T> sys{nf, m_.row_ptr.data(), m_.col.data(), blocks_.data()};
    sys.pressure = &npt_;
    cg::pressure_rows_by_blocks<T, true>(sys, npx_.data(), npc_.data(), par);
#pragma omp parallel for schedule(static) if (par)
    for (int j = 0; j < nf; ++j) {
      const V4 g = cg::pressure_by_blocks(sys, j);
      for (int k = 0; k < 3; ++k) b_[3 * j + k] -= g[k];
      // The diagonal block changes only with row j's couplings, those of the elements at j
      // that were re-rotated (marked in pc_dirty_; all of them at a full assembly).
      if (!pc_all_ && !pc_dirty_[std::size_t(j)]) continue;
      M3 D = M3::Zero();
      for (int k = m_.row_ptr[j]; k < m_.row_ptr[j + 1]; ++k) {
        const Eigen::Map<const V3> bk(&npbt_[3 * std::size_t(k)]);
        D.noalias() += npw_[m_.free_nodes[m_.col[k]]] * bk * bk.transpose();
      }
      for (int q = np_.ft_row_ptr[j]; q < np_.ft_row_ptr[j + 1]; ++q) {
        const Eigen::Map<const V3> bk(&npb_[3 * std::size_t(np_.ft_pair[q])]);
        D.noalias() += npw_[np_.ft_node[q]] * bk * bk.transpose();
      }
      Eigen::Map<M3> dst(&npdiag_[9 * std::size_t(j)]);
      dst = D;
    }
  }

  // R v for R given by its columns, and (R - I) v.
  static V4 rotate(const V4 Rc[3], const T* v) { return lanes::mul<T>(Rc, lanes::load3(v)); }

  // The element pass over `count` elements index(0..count-1) in three stages: F and its
  // check for each, the rotation extraction of those that moved, four at a time
  // (fem::extract_rotation4: independent chains side by side), then their blocks.
  template <class Index>
  void elements(int count, Index index, bool full, bool kept, T tol) {
    int moved[kChunk];
    V4 Fm[kChunk][3];
    int n = 0;
    for (int c = 0; c < count; ++c) {
      const int e = index(c);
      if (deformation(e, full, tol, Fm[n])) moved[n++] = e;
    }
    for (int k0 = 0; k0 < n; k0 += 4) {
      V4 A[9], q[4];
      for (int l = 0; l < 4; ++l) {
        const int k = std::min(k0 + l, n - 1);  // a short last group repeats its last element
        for (int j = 0; j < 3; ++j)
          for (int i = 0; i < 3; ++i) A[3 * j + i][l] = Fm[k][j][i];
        const auto& qe = q_[moved[k]];
        q[0][l] = qe.w();
        q[1][l] = qe.x();
        q[2][l] = qe.y();
        q[3][l] = qe.z();
      }
      fem::extract_rotation4<T>(A, q);
      for (int l = 0; l < 4 && k0 + l < n; ++l) q_[moved[k0 + l]] = Eigen::Quaternion<T>(q[0][l], q[1][l], q[2][l], q[3][l]);
    }
    int thread = 0;  // this thread's trash slot for fixed nodes' rows and blocks
#ifdef _OPENMP
    thread = omp_get_thread_num();
#endif
    for (int k = 0; k < n; ++k) element(moved[k], Fm[k], full, kept, tol, thread);
  }

  // F = sum_a x_a g_a^T of element e into Fc (columns); true when its rotation is to be
  // re-extracted (always when `full`), and then F is kept as the new reference.
  bool deformation(int e, bool full, T tol, V4 Fc[3]) {
    const auto& t = m_.tets[e];
    const std::size_t es = std::size_t(e);
    const T* ge = &eg_[12 * es];
    // Column j of F is sum_a x_a (g_a)_j.
    V4 xa[4];
    for (int a = 0; a < 4; ++a) xa[a] = lanes::load4(&x_[3 * std::size_t(t[a])]);  // lane 3: not used
    for (int j = 0; j < 3; ++j) Fc[j] = xa[0] * ge[j] + xa[1] * ge[3 + j] + xa[2] * ge[6 + j] + xa[3] * ge[9 + j];
    // Two tolerances, both `tol` (max abs entry): the rotation is re-extracted (warm
    // started) when F has moved more than tol since the last extraction, and the
    // element's stiffness blocks in K are re-rotated only when that R has moved more than
    // tol from the rotation they were built with (a push strains far more than it
    // rotates: at 1e-3 about half of the extractions re-rotate K).
    T* Fref = &eF_[12 * es];
    if (!full) {
      const V4 d0 = Fc[0] - lanes::load4(Fref), d1 = Fc[1] - lanes::load4(Fref + 4), d2 = Fc[2] - lanes::load4(Fref + 8);
      const T tt = tol * tol;
      const auto ok = (d0 * d0 <= tt) & (d1 * d1 <= tt) & (d2 * d2 <= tt);  // NaN: not ok
      // Not extracting implies the kept mode (tolerance 0 is always full): K, b0 and the
      // force (b0 - K u) need nothing more of this element.
      if (ok[0] && ok[1] && ok[2]) return false;
    }
    for (int j = 0; j < 3; ++j) lanes::store4(Fref + 4 * j, Fc[j]);
    return true;
  }

  // Element e after its rotation q_[e] was re-extracted for F (columns Fc): its blocks
  // re-rotated if R moved more than tol from theirs, and at tolerance 0 its force.
  void element(int e, const V4 Fc[3], bool full, bool kept, T tol, int thread) {
    const std::size_t es = std::size_t(e);
    const T* ge = &eg_[12 * es];
    const M3 R = q_[e].toRotationMatrix();
    T* Rk = &ekrot_[9 * es];
    const int trash_row = 3 * (m_.num_free() + thread);
    bool update = full;
    if (!update) {
      T change = 0;
      for (int i = 0; i < 9; ++i) change = std::max(change, std::abs(R.data()[i] - Rk[i]));
      update = !(change <= tol);
    }
    if (update) {
      const int trash_blk = 9 * (m_.num_blocks() + thread);
      int blk[16];
      for (int k = 0; k < 16; ++k) {
        const int v = eblk_[16 * es + k];
        blk[k] = v < 0 ? trash_blk : v;
      }
      int rows[4];
      for (int a = 0; a < 4; ++a) {
        const int v = erow_[4 * es + a];
        rows[a] = v < 0 ? trash_row : v;
      }
      const T* X = &eX_[12 * es];
      const V4 Rc[3] = {lanes::load3(R.data()), lanes::load3(R.data() + 3), lanes::load3(R.data() + 6)};
      V4 r[4], y[4];
      for (int a = 0; a < 4; ++a) {
        r[a] = rotate(Rc, ge + 3 * a);
        y[a] = rotate(Rc, X + 3 * a) - lanes::load3(X + 3 * a);
      }
      if (full) {
        rotate_blocks(es, r, kept ? y : nullptr, nullptr, nullptr, blk, rows);
        if (nodal()) rotate_pairs(es, r, nullptr, blk);
      } else {  // the element's old blocks (and its part of b0) out, the new ones in
        const V4 R0[3] = {lanes::load3(Rk), lanes::load3(Rk + 3), lanes::load3(Rk + 6)};
        V4 r0[4], y0[4];
        for (int a = 0; a < 4; ++a) {
          r0[a] = rotate(R0, ge + 3 * a);
          y0[a] = rotate(R0, X + 3 * a) - lanes::load3(X + 3 * a);
        }
        rotate_blocks(es, r, y, r0, y0, blk, rows);
        if (nodal()) rotate_pairs(es, r, r0, blk);
      }
      for (int i = 0; i < 9; ++i) Rk[i] = R.data()[i];
      for (int a = 0; a < 4; ++a)
        if (const int v = erow_[4 * es + a]; v >= 0) pc_dirty_[std::size_t(v / 3)] = 1;  // no two of a colour share one
    }
    if (kept) return;  // the force is -K u + b0 (assemble())
    // Elastic force f_a = -V R sigma(R^T F - I) g_a (fem::element_forces, with R sigma
    // formed once).
    const T vol = evol_[e];
    M3 F;
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) F(i, j) = Fc[j][i];
    const M3 RS = -vol * (R * fem::linear_stress<T>(R.transpose() * F - M3::Identity(), lambda_[e], mu_[e]));
    for (int a = 0; a < 4; ++a) {
      const int v = erow_[4 * es + a];
      T* bb = &b_[std::size_t(v < 0 ? trash_row : v)];
      const V3 f = RS * V3(ge[3 * a], ge[3 * a + 1], ge[3 * a + 2]);
      for (int k = 0; k < 3; ++k) bb[k] += f[k];
    }
  }

  // b = h (f_el - (beta + h) K v + m g - alpha M v), b_ holding f_el - (beta + h) K v
  // (assemble()); contact terms are added after.
  void add_gravity_and_damping_rhs(T h) {
    const T alpha = T(p_.damping.mass);
    for (int i = 0; i < m_.num_free(); ++i) {
      const int node = m_.free_nodes[i];
      const T mass = T(m_.mass[node]);
      for (int k = 0; k < 3; ++k) {
        const T f = b_[3 * i + k] + mass * T(p_.gravity[k]) - alpha * mass * v_[3 * node + k];
        b_[3 * i + k] = h * f;
      }
    }
  }

  // Velocity of a contact point: the barycentric mix of its triangle's nodes.
  Eigen::Vector3d point_velocity(const contact::SurfaceContact& c) const {
    Eigen::Vector3d v = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) v += c.w[k] * Eigen::Vector3d(v_[3 * c.node[k]], v_[3 * c.node[k] + 1], v_[3 * c.node[k] + 2]);
    return v;
  }

  // Contact terms, lumped on the diagonal D: node k of a contact triangle gets w_k of the
  // force and w_k (h^2 ks + h ke) n n^T. (The consistent Jacobian couples the three
  // nodes by w_j w_k; lumping keeps the same response to a translation of the triangle
  // and is stiffer, never softer, for the others: still stable, and the force itself is
  // exact.)
  void add_contacts(std::span<const FingerInput> fingers, T h) {
    const double ks = p_.contact.stiffness, ke = p_.contact.damping;
    // The rows with contact terms in the last solved system and in this one change their
    // diagonal.
    for (int i : contact_rows_) pc_dirty_[std::size_t(i)] = 1;
    contact_rows_.clear();
    for (const auto& c : contacts_) {
      const double rate = -c.n.dot(point_velocity(c) - fingers[c.finger].velocity);
      const double cks = c.scale * ks, cke = c.scale * ke;  // area-weighted (contact_sphere.h)
      const double mag = contact::penalty(cks, cke, c.depth, rate);
      if (mag <= 0) continue;
      const Eigen::Matrix3d nn = c.n * c.n.transpose();
      for (int k = 0; k < 3; ++k) {
        const int node = c.node[k];
        const int i = m_.dof[node];
        if (i < 0 || c.w[k] <= 0) continue;
        const Eigen::Vector3d vn(v_[3 * node], v_[3 * node + 1], v_[3 * node + 2]);
        // Linearised: f(x + h v') ~ f - h ks n n^T v', damping ke n n^T on v'.
        const Eigen::Vector3d rhs = double(h) * c.w[k] * (mag * c.n - double(h) * cks * nn * vn);
        const Eigen::Matrix3d A = c.w[k] * (double(h) * double(h) * cks + double(h) * cke) * nn;
        T* d = &diag_[9 * std::size_t(i)];
        contact_rows_.push_back(i);
        pc_dirty_[std::size_t(i)] = 1;
        for (int r = 0; r < 3; ++r) {
          b_[3 * i + r] += T(rhs[r]);
          for (int s = 0; s < 3; ++s) d[3 * r + s] += T(A(r, s));
        }
      }
    }
  }

  // Forces on the fingers at the end-of-step state, low-pass filtered.
  void finger_outputs(std::span<const FingerInput> fingers, std::span<FingerOutput> out) {
    const double ks = p_.contact.stiffness, ke = p_.contact.damping;
    const double a = force_filter_alpha(p_.contact.force_filter_hz, p_.solver.dt);
    surface_bounds();
    contact::detect<T>(fingers, m_.surface, x_.data(), bounds_, contacts_);
    for (std::size_t f = 0; f < out.size(); ++f) out[f] = FingerOutput{};
    for (const auto& c : contacts_) {
      const double rate = -c.n.dot(point_velocity(c) - fingers[c.finger].velocity);
      const double mag = contact::penalty(c.scale * ks, c.scale * ke, c.depth, rate);
      FingerOutput& o = out[c.finger];
      o.force_raw -= mag * c.n;
      o.stiffness -= c.scale * ks * c.n * c.n.transpose();
      o.contact_point += c.p;
      ++o.contacts;
    }
    for (std::size_t f = 0; f < out.size() && f < fingers.size(); ++f) finish_finger_output(out[f], filtered_[f], a);
  }

  const Model& m_;
  SimParams p_;
  double given_corotation_;                  // the corotation tolerance as given (p_ holds it resolved)
  std::vector<T> x_, v_;                     // (nnode x 3) state
  std::vector<Eigen::Quaternion<T>> q_;      // (ntet) element rotations, warm start
  std::vector<T> lambda_, mu_;               // (ntet) materials in T (lambda 0: in the nodal term)
  Materials mat_;                            // the materials set last (an element change rebuilds from them)
  NodalPressurePattern np_;                  // nodal-pressure element only: its pattern,
  std::vector<int> epair_;                   // (ntet x 16) pair offsets of each element, -1 fixed
  std::vector<T> npb_, npw_;                 // (npair x 3) couplings b_nj, kept like K; (nnode) lambda_n / V_n
  std::vector<T> npi_, npc_;                 // (nnode) pressures (CG scratch), rest-position part c_n
  std::vector<T> npbb_, npbt_;               // (nblock x 3 + trash) the couplings in the block order (cg::PressureTerm)
  std::vector<T> npif_;                      // (nfree) free nodes' pressures (CG scratch)
  std::vector<T> npx_, npdiag_;              // (nfree x 3) u + damp v, (nfree x 9) diagonal blocks of B^T W B
  cg::PressureTerm<T> npt_;
  std::vector<membrane::Rest<T>> skin_rest_;  // (ntri) the skin membrane's rest data in T
  std::vector<T> skin_k_, skin_b0_;          // (ntri x 81, x 9) each triangle's last blocks and b0 part
  std::vector<T> eg_, egg_, evol_;           // (ntet x 12, x 10, x 1) element constants in T
  std::vector<T> eX_;                        // (ntet x 12) rest positions about the element's centroid
  std::vector<int> eblk_, erow_;             // (ntet x 16, x 4) block / row offsets, fixed -> trash
  std::vector<int> eup_;                     // (ntet x 16) upper entry of each block, -1 with a fixed node
  std::vector<int> up_row_ptr_, up_col_;     // the upper triangle's pattern (cg::UpperBlocks)
  std::vector<int> up_of_block_;             // (nblock) the upper entry of each full block
  std::vector<T> ublocks_, ubb_, ubt_;       // (nupper x 9, x 3, x 3) its blocks and couplings, kept beside the full ones
  std::vector<T> uscatter_;                  // (nfree x 4) the upper product's scratch
  cg::UpperBlocks<T> upper_;
  std::vector<T> eF_;                        // (ntet x 12) F's columns (4 lanes) at the last extraction
  std::vector<T> ekrot_;                     // (ntet x 9) the rotation its blocks in K were built with
  std::vector<T> blocks_;                    // (nblock x 9) rotated stiffness K, column-major blocks, kept
  std::vector<T> diag_;                      // (nfree x 9) mass and contact diagonal D, per step
  std::vector<T> b_, dv_, kv_, vfree_;       // (nfree x 3)
  std::vector<T> dvprev_;                    // (nfree x 3) the solution before dv_ (warm start)
  std::vector<T> b0_;                        // (nfree x 3 + trash) sum of K_e (R_e - I) X_e, kept with K
  cg::Workspace<T> cg_;
  std::vector<unsigned char> pc_dirty_;      // (nfree) the row's diagonal block changed since its inverse was taken
  std::vector<int> contact_rows_;            // the rows with contact terms in the last system
  bool pc_all_ = true;                       // every row's (a full assembly)
  T pc_scale_ = -1, pc_mscale_ = -1;         // the scales the inverses were taken with (-1: none yet)
  MultigridKeeper multigrid_;  // the levels below the system (Preconditioner::Multigrid*) and when to rebuild them
  std::vector<contact::SurfaceContact> contacts_;
  std::vector<Eigen::Vector3d> filtered_;    // (nfinger) filtered force
  contact::Bounds bounds_;
  bool rested_ = true;
  bool last_converged_ = false;               // the last CG solve met its tolerance
  int tight_solves_ = 0;                      // count_tight_solves of the last solves (params.h)
  bool assembled_ = false;                   // blocks_ holds K for the current rotations
  long steps_since_assembly_ = 0;
  CpuWorkCounters counters_;
  MultigridCounts multigrid_counts_;
  struct Kept {
    std::vector<T> x, v, dv, dvprev;
    std::vector<Eigen::Quaternion<T>> q;
    std::vector<Eigen::Vector3d> filtered;
    bool rested = true, last_converged = false, valid = false;
    int tight_solves = 0;
  } kept_;                                   // checkpoint()
  std::vector<T> reuse_dv_;                  // rollback_for_reference(): the undone take's solution
  bool reuse_pending_ = false;               // ... which the next take starts from
  int threads_ = 1;                          // OpenMP threads (trash slots; parallel() needs 2)
  unsigned cores_ = std::thread::hardware_concurrency();
};

}  // namespace

namespace {
// f(the CPU backend b is, in its precision), or `other` for any other backend.
template <class R, class F>
R on_cpu_backend(const Backend& b, R other, F f) {
  if (const auto* d = dynamic_cast<const CpuBackend<double>*>(&b)) return f(*d);
  if (const auto* s = dynamic_cast<const CpuBackend<float>*>(&b)) return f(*s);
  return other;
}
}  // namespace

CpuWorkCounters cpu_work_counters(const Backend& b) {
  return on_cpu_backend(b, CpuWorkCounters{}, [](const auto& c) { return c.counters(); });
}

double cpu_preconditioner_staleness(const Backend& b) {
  return on_cpu_backend(b, -1.0, [](const auto& c) { return c.preconditioner_staleness(); });
}

std::unique_ptr<Backend> make_cpu_backend(const Model& model, const SimParams& params) {
  if (params.solver.precision == Precision::Float) return std::make_unique<CpuBackend<float>>(model, params);
  return std::make_unique<CpuBackend<double>>(model, params);
}

}  // namespace palpation::sim
