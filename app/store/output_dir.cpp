#include "store/output_dir.h"

#include <filesystem>
#include <stdexcept>
#include <system_error>
#include <unistd.h>

namespace palpation::app::store {

namespace fs = std::filesystem;

OutputDir::OutputDir(const std::string& dir) : dir_(dir) {
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec || !fs::is_directory(dir_)) throw std::runtime_error(dir_ + ": cannot create the output folder (" + ec.message() + ")");
  staging_ = (fs::path(dir_) / (".staging-" + std::to_string(::getpid()))).string();
  fs::remove_all(staging_, ec);
  fs::create_directories(staging_, ec);
  if (ec) throw std::runtime_error(dir_ + ": cannot write in the output folder (" + ec.message() + ")");
}

OutputDir::~OutputDir() {
  std::error_code ec;
  fs::remove_all(staging_, ec);
}

std::string OutputDir::path(const std::string& name) const { return (fs::path(staging_) / name).string(); }

void OutputDir::commit() {
  for (const auto& e : fs::directory_iterator(staging_)) fs::rename(e.path(), fs::path(dir_) / e.path().filename());
  std::error_code ec;
  fs::remove_all(staging_, ec);
  committed_ = true;
}

}  // namespace palpation::app::store
