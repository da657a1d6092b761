#include "live/levels_builder.h"

namespace palpation::app::live {

LevelsBuilder::~LevelsBuilder() {
  if (current_.thread.joinable()) current_.thread.join();
  for (Run& r : forgotten_) r.thread.join();
}

void LevelsBuilder::join_finished() {
  for (auto it = forgotten_.begin(); it != forgotten_.end();) {
    if (it->job->done()) {
      it->thread.join();
      it = forgotten_.erase(it);
    } else {
      ++it;
    }
  }
}

bool LevelsBuilder::poll(sim::Backend& backend) {
  bool installed = false;
  if (current_.job && current_.job->done()) {
    current_.thread.join();
    // False when the backend's system changed since the job was taken: the backend then
    // hands out a new job below.
    installed = backend.install_levels(current_.job);
    current_ = {};
  }
  if (!forgotten_.empty()) join_finished();
  if (!current_.job) {
    if (auto job = backend.take_levels_job()) {
      current_.job = job;
      current_.thread = std::thread([job] { job->run(); });
      ++started_;
    }
  }
  return installed;
}

void LevelsBuilder::forget() {
  if (current_.job) forgotten_.push_back(std::move(current_));
  current_ = {};
}

}  // namespace palpation::app::live
