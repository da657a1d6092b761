// Output folders that never hold half a result: files are written into a hidden staging
// folder inside DIR and moved into place only when the whole command succeeded.
#pragma once

#include <string>

namespace palpation::app::store {

class OutputDir {
 public:
  /// Creates DIR (and parents) and a staging folder in it. Throws std::runtime_error
  /// naming the folder when it cannot be created.
  explicit OutputDir(const std::string& dir);
  /// Removes the staging folder unless commit() was called: nothing half written stays.
  ~OutputDir();
  OutputDir(const OutputDir&) = delete;
  OutputDir& operator=(const OutputDir&) = delete;

  /// Path to write `name` to (inside the staging folder).
  std::string path(const std::string& name) const;
  /// Moves every staged file into DIR (replacing older ones), removes the staging folder.
  void commit();
  const std::string& dir() const { return dir_; }

 private:
  std::string dir_, staging_;
  bool committed_ = false;
};

}  // namespace palpation::app::store
