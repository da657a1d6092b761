// libFuzzer target: the session recording reader (app/store/recording.cpp). Any file
// either reads into a recording or throws RecordingError with a one-line message naming
// the file; recover_recording on it either recovers or throws RecordingError. Nothing
// else (another exception, a crash, a sanitizer report) is acceptable.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "store/recording.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace palpation::app::store;
  static const std::string path = "/tmp/palpation-fuzz-rec-" + std::to_string(::getpid()) + ".prec";
  auto write = [&] {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) return false;
    if (size) std::fwrite(data, 1, size, f);
    std::fclose(f);
    return true;
  };
  if (!write()) return 0;
  try {
    (void)read_recording(path);
  } catch (const RecordingError& e) {
    if (std::string(e.what()).find('\n') != std::string::npos) std::abort();
  }
  if (!write()) return 0;
  try {
    (void)recover_recording(path);
  } catch (const RecordingError& e) {
    if (std::string(e.what()).find('\n') != std::string::npos) std::abort();
  }
  return 0;
}
