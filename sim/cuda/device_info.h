// The CUDA device this process uses (device 0), detected once (sim/cuda/backend_cuda.cu).
#pragma once

#include <string>

namespace palpation::sim::cuda {

struct DeviceInfo {
  bool ok = false;  // usable: compute capability >= 6.0, cooperative launches, a context
  std::string why;  // why not, in one line
  std::string name;
  int device = 0;
  int sms = 0;
  int cc_major = 0, cc_minor = 0;
  bool cooperative = false;
};

/// Detects the device on the first call (thread-safe) and returns the same answer after.
const DeviceInfo& device_info();

}  // namespace palpation::sim::cuda
