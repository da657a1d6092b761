// CudaTuning::from_environment: the one place where the CUDA backends read the environment.
#include "cuda/tuning.h"

#include <algorithm>
#include <cstdlib>
#include <string>

namespace palpation::sim::cuda {

namespace {

int env_int(const char* name, int fallback) {
  const char* s = std::getenv(name);
  if (!s || !*s) return fallback;
  return std::atoi(s);
}

std::string env_str(const char* name, const std::string& fallback) {
  const char* s = std::getenv(name);
  return (s && *s) ? std::string(s) : fallback;
}

}  // namespace

CudaTuning CudaTuning::from_environment() {
  CudaTuning t;
  t.pcg_block = env_int("PALPATION_CUDA_PCG_BLOCK", 512) == 256 ? 256 : 512;
  t.pcg_grid = env_int("PALPATION_CUDA_GRID", 0);
  t.pcg_blocks_per_sm = env_int("PALPATION_CUDA_BLOCKS_PER_SM", 0);
  t.rows_in_registers = env_int("PALPATION_CUDA_CACHE", 1) != 0;
  const std::string cg = env_str("PALPATION_CUDA_CG", "auto");
  t.cg_form = cg == "3sync"   ? CudaTuning::CgForm::ThreeBarriers
              : cg == "fused" ? CudaTuning::CgForm::Fused
              : cg == "1sync" ? CudaTuning::CgForm::OneReduction
                              : CudaTuning::CgForm::Auto;
  t.shadow_sms = env_int("PALPATION_CUDA_SHADOW_SMS", 0);
  const std::string place = env_str("PALPATION_CUDA_SHADOW", "confined");
  t.shadow_place = place == "full"     ? CudaTuning::ShadowPlace::Full
                   : place == "sliced" ? CudaTuning::ShadowPlace::Sliced
                                       : CudaTuning::ShadowPlace::Confined;
  t.shadow_slice = std::max(1, env_int("PALPATION_CUDA_SHADOW_SLICE", 8));
  t.shadow_slice_mg = std::max(1, env_int("PALPATION_CUDA_SHADOW_SLICE_MG", 2));
  const std::string lanes = env_str("PALPATION_CUDA_MG_LANES", "auto");
  t.mg_lanes = lanes == "2" ? 2 : lanes == "8" ? 8 : lanes == "block" ? 0 : -1;
  t.profile = env_int("PALPATION_CUDA_PROFILE", 0) != 0;
  t.phases = env_int("PALPATION_CUDA_PHASES", 0) != 0;
  return t;
}

}  // namespace palpation::sim::cuda
