#include "simulation.h"

#include "tissue_layers.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <cstdio>
#include <stdexcept>

namespace palpation::sim {

int apply_inclusions(Model& m, const std::vector<Inclusion>& inclusions) {
  int changed = 0;
  for (int e = 0; e < m.num_tets(); ++e) {
    const auto& t = m.tets[e];
    const Eigen::Vector3d c = 0.25 * (m.rest[t[0]] + m.rest[t[1]] + m.rest[t[2]] + m.rest[t[3]]);
    for (const auto& inc : inclusions)
      if (inc.contains(c)) {
        // An inclusion of the tissue itself (the paper sweep's no-tumour twin: the same
        // refined mesh, no tumour) keeps each element's tissue, its layer's in a layered one.
        const bool tissue = inc.young_modulus == m.tissue.young_modulus && inc.poisson_ratio == m.tissue.poisson_ratio;
        if (!tissue) m.set_element_material(e, inc.young_modulus, inc.poisson_ratio);
        ++changed;
        break;
      }
  }
  return changed;
}

double tet_quality(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                   const Eigen::Vector3d& d) {
  const double l2 = (b - a).squaredNorm() + (c - a).squaredNorm() + (d - a).squaredNorm() + (c - b).squaredNorm() +
                    (d - b).squaredNorm() + (d - c).squaredNorm();
  if (!(l2 > 0)) return 0;
  const double lrms = std::sqrt(l2 / 6);
  return 6 * std::sqrt(2.0) * std::abs(tet_volume(a, b, c, d)) / (lrms * lrms * lrms);
}

double min_tet_quality(const TetMesh& m, int* worst) {
  double q = 1e300;
  for (int e = 0; e < m.num_tets(); ++e) {
    const auto& t = m.tets[e];
    const double qe = tet_quality(m.nodes[t[0]], m.nodes[t[1]], m.nodes[t[2]], m.nodes[t[3]]);
    if (!(qe >= q)) {
      q = qe;
      if (worst) *worst = e;
    }
  }
  return q;
}

Model build_scenario_model(const Scenario& s, TetMesh mesh) {
  if (!s.patient.mesh.empty()) {
    int e = -1;
    const double q = min_tet_quality(mesh, &e);
    if (!(q >= kMinTetQuality)) {
      char buf[200];
      std::snprintf(buf, sizeof buf, ": tetrahedron %d is a sliver (quality %.3g < %.3g; docs/stability.md)", e, q,
                    kMinTetQuality);
      throw ScenarioError(s.source + ": patient.mesh: " + s.patient.mesh + buf);
    }
  }
  Material tissue{s.young_modulus, s.poisson_ratio, s.density};
  double zmin = std::numeric_limits<double>::max();
  for (const auto& p : mesh.nodes) zmin = std::min(zmin, p.z());
  Model m = build_model(std::move(mesh), tissue, fix_base(zmin + 1e-6));
  apply_layers(m, s.layers);
  apply_skin(m, s.skin);
  apply_inclusions(m, s.inclusions);
  return m;
}

BackendKind parse_backend_kind(const std::string& name) {
  if (name == "cpu") return BackendKind::Cpu;
  if (name == "cuda") return BackendKind::Cuda;
  return BackendKind::Auto;
}

Simulation::Simulation(const Scenario& s, const LogFn& log) : s_(s) {
  model_ = build_scenario_model(s_, patient_mesh(s_, log));
  init(log);
}

Simulation::Simulation(const Scenario& s, Model model, const LogFn& log) : s_(s), model_(std::move(model)) {
  init(log);
}

void Simulation::init(const LogFn& log) {
  log_ = log;
  materials_ = model_.materials;
  if (model_.num_nodes() > 0) {
    Eigen::Vector3d lo = model_.rest[0], hi = model_.rest[0];
    for (const auto& p : model_.rest) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    diagonal_ = (hi - lo).norm();
  }
  SimParams p = s_.params;
  backend_ = make_backend(parse_backend_kind(s_.backend), model_, p, &reason_);
  if (log && !reason_.empty()) log("backend: " + reason_);
  fingers_.resize(s_.fingers.size());
  outputs_.resize(s_.fingers.size());
  for (std::size_t i = 0; i < s_.fingers.size(); ++i) fingers_[i].radius = s_.fingers[i].radius;
  prepare_shadow();
}

StepStats Simulation::step() {
  const double t1 = t_ + s_.params.solver.dt;
  for (std::size_t i = 0; i < s_.fingers.size(); ++i) s_.fingers[i].sample(t1, fingers_[i].position, fingers_[i].velocity);
  return advance(fingers_, outputs_, s_.params.solver.dt).stats;
}

Simulation::Outcome Simulation::advance(std::span<const FingerInput> in, std::span<FingerOutput> out, double h) {
  if (backend_->params().solver.dt != h) {
    SimParams p = backend_->params();
    p.solver.dt = h;
    backend_->set_params(p);
  }
  Outcome r;
  try {
    r.stats = controlled_step(in, out);
  } catch (const std::exception& e) {
    // The CPU backend keeps the parameters (dt and threads included) of the one it replaces.
    if (!fall_back_to_cpu(e.what())) throw;
    r.fell_back = true;
    r.error = e.what();
    r.stats = controlled_step(in, out);
  }
  step_check_on();
  t_ += h;
  ++steps_;
  r.ok = !check_divergence(r.stats, out).diverged;
  if (r.ok)
    for (const auto& o : out)
      if (!(o.force.allFinite() && o.stiffness.allFinite())) {
        // With the guard disabled a non-finite contact output still never leaves the step.
        backend_->reset();
        r.ok = false;
        break;
      }
  if (!r.ok) {
    r.stats.finite = false;
    for (auto& o : out) o = FingerOutput{};
    // A tolerance the body blew up at is too loose, whatever the checks said.
    if (control_.on()) control_.checked(INFINITY);
  }
  return r;
}

StepStats Simulation::controlled_step(std::span<const FingerInput> in, std::span<FingerOutput> out) {
  SimParams p = backend_->params();
  // Parameters set from outside (the workstation's panel, a new scenario) restart the
  // controller from their tolerance; the tolerance it set itself is its own.
  if (p.solver.force_error != control_.target() || (control_.on() && p.solver.cg_tolerance != control_set_tol_)) {
    control_.start(p.solver.force_error, p.solver.cg_tolerance, backend_->precision());
    control_set_tol_ = -1;
    rescue_base_ = p.solver.cg_rescue_tolerance;
    cap_base_ = p.solver.cg_max_iterations;
  }
  if (!control_.on()) return backend_->step(in, out);
  // A check beside the steps that has finished is scored before this step's tolerance is set.
  collect_check();
  // A capped solve is still rescued (SolverParams::cg_rescue_tolerance), but to no
  // tighter than the tolerance the controller chose: a rescue to 1e-3 would make every
  // looser tolerance 1e-3. The check's reference solve is rescued to its own tolerance
  // (and may go to cg_rescue_iterations): a reference stopped at the cap would read low.
  auto set_tolerance = [&](double tol, bool reference) {
    const double rescue = reference ? tol : std::max(rescue_base_, tol);
    const int cap = reference ? std::max(cap_base_, p.solver.cg_rescue_iterations) : cap_base_;
    if (p.solver.cg_tolerance == tol && p.solver.cg_rescue_tolerance == rescue && p.solver.cg_max_iterations == cap) return;
    p.solver.cg_tolerance = tol;
    p.solver.cg_rescue_tolerance = rescue;
    p.solver.cg_max_iterations = cap;
    backend_->set_params(p);
  };
  set_tolerance(control_.tolerance(), false);
  control_set_tol_ = control_.tolerance();
  // A check needs a step in contact to compare: it follows one (a skipped step at rest
  // costs nothing, and no checkpoint is taken then).
  if (!(last_contact_ && control_.check_due() && !pending_check_.on && backend_->checkpoint())) {
    const StepStats st = backend_->step(in, out);
    const bool began = st.contacts > 0 && !last_contact_;
    last_contact_ = st.contacts > 0;
    if (last_contact_) control_.count_contact_step(began);
    return st;
  }
  loose_.resize(out.size());
  const StepStats loose = backend_->step(in, loose_);
  last_contact_ = loose.contacts > 0;
  if (!last_contact_) {
    // Nothing to compare: the finger has left.
    std::copy(loose_.begin(), loose_.end(), out.begin());
    return loose;
  }
  control_.count_contact_step(false);
  if (loose.finite && check_beside() && start_check_beside(in)) {
    std::copy(loose_.begin(), loose_.end(), out.begin());  // the loose step is the one kept
    return loose;
  }
  backend_->rollback_for_reference();  // the reference solve goes on from the loose solution
  StepStats st;
  try {
    set_tolerance(control_.reference_tolerance(), true);
    st = backend_->step(in, out);
  } catch (...) {
    // The backend failed (a CUDA error): whatever replaces it takes the controller's
    // tolerance, not the reference's.
    set_tolerance(control_.tolerance(), false);
    throw;
  }
  // A loose step that blew up is an infinite error; a reference that did not reach its
  // tolerance measures nothing (the check is not scored); forces on neither side (the
  // finger left during the step) neither.
  const std::optional<double> e = loose.finite ? finger_force_error(loose_, out) : std::optional<double>(INFINITY);
  const bool reference_met = st.finite && st.cg_residual <= 1.0001 * control_.reference_tolerance();
  if (e && (reference_met || !loose.finite))
    control_.checked(*e);
  else
    control_.deferred();
  set_tolerance(control_.tolerance(), false);
  control_set_tol_ = control_.tolerance();
  st.cg_iterations += loose.cg_iterations;  // the work of the step, both solves
  return st;
}

// Under auto the backend's make_shadow decides (null where the steps would gain nothing).
bool Simulation::check_beside() const { return backend_->params().solver.check != CheckPlace::InStep; }

SimParams Simulation::shadow_params() const {
  // The backend's parameters (dt, contact, element as they are now), solved as the in-step
  // check's reference is: to the reference tolerance, rescued to it, with the rescue's
  // cap. Block-Jacobi: a multigrid's levels would be built again for the shadow (seconds on
  // the large meshes), and the shadow's solve is off the steps' path.
  SimParams p = backend_->params();
  p.solver.cg_tolerance = control_.on() ? control_.reference_tolerance()
                                        : p.solver.cg_tolerance * ToleranceController::kReferenceFactor;
  p.solver.cg_rescue_tolerance = p.solver.cg_tolerance;
  p.solver.cg_max_iterations = std::max(cap_base_, p.solver.cg_rescue_iterations);
  p.solver.preconditioner = Preconditioner::BlockJacobi;
  return p;
}

void Simulation::prepare_shadow() {
  if (shadow_ || shadow_failed_ || !(backend_->params().solver.force_error > 0) || !check_beside()) return;
  try {
    shadow_ = backend_->make_shadow(shadow_params());
    if (!shadow_) shadow_failed_ = true;  // this backend cannot: every check in the step
  } catch (const std::exception& e) {
    // No room for a second backend (device memory on the large meshes).
    shadow_off(e);
  }
}

void Simulation::shadow_off(const std::exception& e) {
  pending_check_.on = false;
  shadow_.reset();
  shadow_failed_ = true;
  if (log_) log_(std::string("error control: the check beside the steps is off: ") + e.what());
}

bool Simulation::start_check_beside(std::span<const FingerInput> in) {
  prepare_shadow();  // made when the patient loaded, unless the controller was off then
  if (!shadow_) return false;
  const SimParams p = shadow_params();
  try {
    shadow_->set_params(p);
    if (!backend_->fork_reference(*shadow_)) return false;
    shadow_->begin_step(in);
  } catch (const std::exception& e) {
    shadow_off(e);  // the backend's own state is untouched by a failed fork
    return false;
  }
  pending_check_.on = true;
  pending_check_.tolerance = p.solver.cg_tolerance;
  pending_loose_ = loose_;
  return true;
}

void Simulation::collect_check() {
  if (!pending_check_.on || !shadow_->step_ready()) return;
  pending_check_.on = false;
  reference_.resize(pending_loose_.size());
  StepStats st;
  try {
    st = shadow_->finish_step(reference_);
  } catch (...) {
    shadow_.reset();
    throw;
  }
  // As in the step: a reference that did not reach its tolerance measures nothing.
  const std::optional<double> e = finger_force_error(pending_loose_, reference_);
  if (e && st.finite && st.cg_residual <= 1.0001 * pending_check_.tolerance)
    control_.checked(*e);
  else
    control_.deferred();
}

void Simulation::step_check_on() {
  if (!pending_check_.on) return;
  try {
    shadow_->step_on();
  } catch (const std::exception& e) {
    shadow_off(e);  // as a failed fork: the check in flight goes with the shadow
  }
}

void Simulation::drop_check() {
  if (!pending_check_.on) return;
  pending_check_.on = false;
  try {
    reference_.resize(pending_loose_.size());
    shadow_->finish_step(reference_);
  } catch (const std::exception&) {
    // A shadow that failed goes with its check; the backend reports its own errors.
    shadow_.reset();
  }
}

void Simulation::drop_shadow() {
  drop_check();
  shadow_.reset();
  shadow_failed_ = false;
}

DivergenceCheck Simulation::check_divergence(const StepStats& st, std::span<const FingerOutput> out) {
  const DivergenceCheck prev = check_;
  check_ = DivergenceCheck{};
  DivergenceCheck& c = check_;
  if (!limits_.enabled) return c;
  if (!st.finite) c.reason = "non-finite solver state";
  for (const auto& o : out)
    if (c.reason.empty() && !(o.force.allFinite() && o.force_raw.allFinite() && o.stiffness.allFinite()))
      c.reason = "non-finite finger force";
  if (c.reason.empty()) {
    bool finite = true;
    if (st.max_speed >= 0) {
      // Formed within the step by the backend: no read-back of the state.
      c.max_speed = st.max_speed;
      c.max_displacement = st.max_displacement;
      c.kinetic_energy = st.kinetic_energy;
      finite = std::isfinite(c.max_speed) && std::isfinite(c.max_displacement) && std::isfinite(c.kinetic_energy);
    } else if (!st.solved && summary_known_) {
      // A skipped step leaves the state as the last check saw it (at rest: no speed).
      c.max_displacement = prev.max_displacement;
    } else {
      ++readbacks_;
      backend_->positions(xyz_);
      backend_->velocities(vel_);
      const int n = model_.num_nodes();
      double v2max = 0, d2max = 0, ke = 0;
      for (int i = 0; i < n && i * 3 + 2 < int(xyz_.size()) && i * 3 + 2 < int(vel_.size()); ++i) {
        const Eigen::Vector3d x(xyz_[3 * i], xyz_[3 * i + 1], xyz_[3 * i + 2]);
        const Eigen::Vector3d v(vel_[3 * i], vel_[3 * i + 1], vel_[3 * i + 2]);
        if (!x.allFinite() || !v.allFinite()) {
          finite = false;
          break;
        }
        v2max = std::max(v2max, v.squaredNorm());
        d2max = std::max(d2max, (x - model_.rest[i]).squaredNorm());
        if (i < int(model_.mass.size())) ke += 0.5 * model_.mass[i] * v.squaredNorm();
      }
      c.max_speed = std::sqrt(v2max);
      c.max_displacement = std::sqrt(d2max);
      c.kinetic_energy = ke;
    }
    summary_known_ = finite;
    char buf[160];
    if (!finite) {
      c.reason = "non-finite node position or velocity";
    } else if (c.max_speed > limits_.max_speed) {
      std::snprintf(buf, sizeof buf, "node speed %.3g m/s > %.3g m/s", c.max_speed, limits_.max_speed);
      c.reason = buf;
    } else if (diagonal_ > 0 && c.max_displacement > limits_.max_displacement_factor * diagonal_) {
      std::snprintf(buf, sizeof buf, "node displacement %.3g m > %.3g m", c.max_displacement,
                    limits_.max_displacement_factor * diagonal_);
      c.reason = buf;
    }
  }
  if (!c.reason.empty()) {
    c.diverged = true;
    ++divergences_;
    summary_known_ = false;
    backend_->reset();
    if (log_) {
      char buf[96];
      std::snprintf(buf, sizeof buf, "divergence at t = %.6g s (step %d): ", t_, steps_);
      log_(buf + c.reason + "; body reset to rest");
    }
  }
  return c;
}

bool Simulation::fall_back_to_cpu(const std::string& why) {
  if (!backend_ || backend_->name() == "cpu") return false;
  drop_shadow();
  const std::string was = backend_->name();
  SimParams p = backend_->params();
  // A preconditioner the GPU's size rule chose is chosen again for the CPU (block-Jacobi).
  if (s_.params.solver.preconditioner == Preconditioner::Auto) p.solver.preconditioner = Preconditioner::Auto;
  auto cpu = make_backend(BackendKind::Cpu, model_, p);
  cpu->set_materials(materials_);
  cpu->reset();
  cpu->set_deferred_levels(deferred_levels_);
  backend_ = std::move(cpu);
  ++fallbacks_;
  prepare_shadow();
  reason_ = "fell back from " + was + " to cpu: " + why;
  if (log_) log_("backend: " + reason_);
  return true;
}

int Simulation::set_element_young(std::span<const std::pair<int, double>> changes) {
  int n = 0;
  for (const auto& [e, E] : changes)
    if (e >= 0 && e < model_.num_tets() && std::isfinite(E) && E > 0) {
      materials_.set(e, E, materials_.poisson[std::size_t(e)]);
      ++n;
    }
  if (n > 0) {
    drop_check();  // it measured the old materials
    backend_->set_materials(materials_);
    if (shadow_) shadow_->set_materials(materials_);
  }
  return n;
}

void Simulation::reset() {
  drop_check();  // the shadow stays: the same body, the next fork gives it its state
  backend_->reset();
  backend_->prepare_solver();  // a multigrid's levels at load, not at the first touch
  summary_known_ = false;
  last_contact_ = false;  // the controller keeps its tolerance: the same body, the same solver
  t_ = 0;
  steps_ = 0;
}

}  // namespace palpation::sim
