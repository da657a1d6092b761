#include "backend.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "backend_cpu.h"

#ifdef PALPATION_HAVE_CUDA
#include "backend_cuda.h"
#endif

namespace palpation::sim {

bool cuda_available(std::string* why_not) {
#ifdef PALPATION_HAVE_CUDA
  return cuda_probe(why_not);
#else
  if (why_not) *why_not = "this build has no CUDA backend";
  return false;
#endif
}

std::vector<std::string> available_backends() {
  std::vector<std::string> out{"cpu"};
  if (cuda_available()) {
    out.push_back("cuda");
    out.push_back("cuda-csr");
    out.push_back("cuda-bsr");
  }
  return out;
}

void Backend::begin_step(std::span<const FingerInput> fingers) {
  begun_out_.assign(fingers.size(), FingerOutput{});
  begun_stats_ = step(fingers, begun_out_);
}

StepStats Backend::finish_step(std::span<FingerOutput> out) {
  std::copy_n(begun_out_.begin(), std::min(begun_out_.size(), out.size()), out.begin());
  return begun_stats_;
}

void finish_finger_output(FingerOutput& o, Eigen::Vector3d& filtered, double filter_alpha) {
  if (o.contacts > 0) o.contact_point /= o.contacts;
  const double fn = o.force_raw.norm();
  o.normal = fn > 0 ? Eigen::Vector3d(o.force_raw / fn) : Eigen::Vector3d::Zero();
  filtered += filter_alpha * (o.force_raw - filtered);
  o.force = filtered;
}

double force_filter_alpha(double hz, double dt) {
  constexpr double kPi = 3.14159265358979323846;
  return 1.0 - std::exp(-2.0 * kPi * hz * dt);
}

bool is_library_baseline(const std::string& name) { return name == "cuda-csr" || name == "cuda-bsr"; }

std::string library_baseline_refusal(const std::string& name, const SimParams& params) {
  return is_library_baseline(name) && is_multigrid(params.solver.preconditioner)
             ? "backend " + name + ": solver.preconditioner \"" +
                   std::string(preconditioner_name(params.solver.preconditioner)) +
                   "\" runs on the cpu and cuda backends (the library baselines precondition with block-Jacobi)"
             : std::string();
}

std::unique_ptr<Backend> make_named_backend(const std::string& name, const Model& model, const SimParams& params) {
  if (name == "cpu") return make_cpu_backend(model, params);
#ifdef PALPATION_HAVE_CUDA
  std::string why;
  if (name == "cuda" || is_library_baseline(name)) {
    if (const std::string no = library_baseline_refusal(name, params); !no.empty()) throw std::runtime_error(no);
    if (!cuda_available(&why)) throw std::runtime_error("backend " + name + ": " + why);
    return name == "cuda" ? make_cuda_backend(model, params) : make_cuda_baseline_backend(name, model, params);
  }
#endif
  throw std::runtime_error("backend \"" + name + "\" is not available in this build");
}

bool cuda_floor(const Model& model, Precision precision, FloorEstimate& out) {
#ifdef PALPATION_HAVE_CUDA
  if (!cuda_available()) return false;
  return cuda_measure_floor(model, precision, out);
#else
  (void)model;
  (void)precision;
  (void)out;
  return false;
#endif
}

std::unique_ptr<Backend> make_backend(BackendKind kind, const Model& model, const SimParams& params,
                                      std::string* reason) {
  std::string why;
  if (kind == BackendKind::Cuda || kind == BackendKind::Auto) {
    if (cuda_available(&why)) {
#ifdef PALPATION_HAVE_CUDA
      auto b = make_cuda_backend(model, params);
      if (reason) *reason = "cuda on " + b->device_name();
      return b;
#endif
    }
    if (kind == BackendKind::Cuda) throw std::runtime_error("solver.backend: cuda was asked for but " + why);
  }
  auto b = make_cpu_backend(model, params);
  if (reason) *reason = kind == BackendKind::Auto ? "cpu (" + why + ")" : "cpu";
  return b;
}

}  // namespace palpation::sim
