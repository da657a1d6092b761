// Contact stage: the stand-alone detection kernel (see contact.cuh).
#include "cuda/contact.cuh"

namespace palpation::sim::cuda {

namespace {

/// Stand-alone detection. start = 1: start of step (system terms, contact count, zero the
/// step scratch) and finger sums (the outputs when the step is skipped at rest).
/// start = 0: finger outputs of the end state (baseline path). The last block to finish
/// writes the result.
template <class T>
__global__ void __launch_bounds__(kBlock) k_detect(DetectArgs<T> a, FingersArg F, StepConsts k, int start) {
  __shared__ double sacc[kMaxFingers * kFingerVals];
  __shared__ int scount;
  __shared__ bool last;
  for (int t = threadIdx.x; t < kMaxFingers * kFingerVals; t += blockDim.x) sacc[t] = 0.0;
  if (threadIdx.x == 0) scount = 0;
  if (start && blockIdx.x == 0 && threadIdx.x == 0) zero_step_scratch(a.scr);
  __syncthreads();
  detect_nodes(a, F, k, start != 0, sacc, &scount, blockIdx.x * blockDim.x + threadIdx.x, gridDim.x * blockDim.x);
  if (!start) zero_contact_terms(a, blockIdx.x * blockDim.x + threadIdx.x, gridDim.x * blockDim.x);
  __syncthreads();
  for (int t = threadIdx.x; t < F.n * kFingerVals; t += blockDim.x)
    if (sacc[t] != 0.0) atomicAdd(&a.scr->facc[0][0] + t, sacc[t]);
  if (threadIdx.x == 0 && scount) atomicAdd(&a.scr->start_contacts, scount);
  __threadfence();
  __syncthreads();
  if (threadIdx.x == 0) last = atomicAdd(&a.scr->detect_done, 1u) == gridDim.x - 1;
  __syncthreads();
  if (last) finalize_result(a.scr, a.res, !start);
}

}  // namespace

template <class T>
void launch_detect(cudaStream_t s, int grid, const DetectArgs<T>& a, const FingersArg& F, const StepConsts& k,
                   bool start) {
  k_detect<T><<<grid, kBlock, 0, s>>>(a, F, k, start ? 1 : 0);
  CU_LAUNCHED(k_detect);
}

template void launch_detect<float>(cudaStream_t, int, const DetectArgs<float>&, const FingersArg&, const StepConsts&,
                                   bool);
template void launch_detect<double>(cudaStream_t, int, const DetectArgs<double>&, const FingersArg&, const StepConsts&,
                                    bool);

}  // namespace palpation::sim::cuda
