// Fault injection for tests: a backend that wraps a real one and, from a given
// step on, fails the way a GPU backend can: throws (a CUDA error), returns NaN, or
// reports a blown-up state (node velocities scaled up).
#pragma once

#include <chrono>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>

#include "backend.h"

namespace palpation::test {

class FaultBackend : public sim::Backend {
 public:
  enum class Fault { None, Throw, NaN, BlowUp };
  /// slow_s: every step from the faulty one on first sleeps that long (a loaded machine
  /// that deschedules the simulation thread).
  FaultBackend(std::unique_ptr<sim::Backend> inner, Fault fault, int at_step, std::string name = "cuda", double slow_s = 0)
      : inner_(std::move(inner)), fault_(fault), at_(at_step), name_(std::move(name)), slow_s_(slow_s) {}

  std::string name() const override { return name_; }
  std::string device_name() const override { return "fault-injected " + inner_->device_name(); }
  sim::Precision precision() const override { return inner_->precision(); }
  void reset() override {
    blown_ = false;
    inner_->reset();
  }
  sim::StepStats step(std::span<const sim::FingerInput> f, std::span<sim::FingerOutput> out) override {
    const int k = steps_++;
    if (k >= at_ && slow_s_ > 0) std::this_thread::sleep_for(std::chrono::duration<double>(slow_s_));
    if (k == at_ || (fault_ == Fault::Throw && k > at_)) {
      if (fault_ == Fault::Throw) throw std::runtime_error("injected CUDA error: an illegal memory access was encountered");
      sim::StepStats st = inner_->step(f, out);
      if (fault_ == Fault::NaN) {
        st.finite = false;
        for (auto& o : out) o.force.x() = std::numeric_limits<double>::quiet_NaN();
      }
      if (fault_ == Fault::BlowUp) blown_ = true;
      return blow_up(st);
    }
    return blow_up(inner_->step(f, out));
  }
  void positions(std::vector<double>& xyz) const override { inner_->positions(xyz); }
  void velocities(std::vector<double>& v) const override {
    inner_->velocities(v);
    if (blown_)
      for (std::size_t i = 0; i < v.size(); ++i) v[i] += (i % 3 == 2) ? 1e3 : 0.0;
  }
  void set_materials(const sim::Materials& m) override { inner_->set_materials(m); }
  void set_params(const sim::SimParams& p) override { inner_->set_params(p); }
  const sim::SimParams& params() const override { return inner_->params(); }
  int steps() const { return steps_; }

 private:
  // A blown-up state as the step's own summary reports it (the guard's no-read-back path)
  // and as velocities() returns it (the read-back path).
  sim::StepStats blow_up(sim::StepStats st) const {
    if (blown_ && st.max_speed >= 0) st.max_speed += 1e3;
    return st;
  }

 private:
  std::unique_ptr<sim::Backend> inner_;
  Fault fault_;
  int at_;
  std::string name_;
  double slow_s_ = 0;
  int steps_ = 0;
  bool blown_ = false;
};

}  // namespace palpation::test
