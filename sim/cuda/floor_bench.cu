// The floor of the fast CUDA backend ("cuda") on a model, for `palpation bench`: what one
// CG iteration and the rest of a step cannot go below on this device. It counts the bytes
// the iteration must move and the grid-wide barriers it needs (the launch plan of
// pcg.cuh), and measures the bandwidth at that working-set size and the barrier cost with
// the same launch configuration. Once per process it also prints (stderr) the
// alternatives to a grid barrier that docs/gpu-notes.md compares: a kernel boundary in a
// stream and in a replayed CUDA graph, and a host round trip.
#include <cooperative_groups.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <mutex>
#include <vector>

#include "backend_cuda.h"
#include "cuda/common.cuh"
#include "cuda/device_info.h"
#include "cuda/element.cuh"
#include "cuda/pcg.cuh"
#include "cuda/tuning.h"

namespace palpation::sim {
namespace cuda {

namespace {

namespace coop = cooperative_groups;

// Floor measurement kernels.

template <class T>
__global__ void __launch_bounds__(kBlock) k_stream_passes(const T* __restrict__ in, T* __restrict__ out, std::size_t n,
                                                           int passes) {
  coop::grid_group grid = coop::this_grid();
  const std::size_t tid = blockIdx.x * std::size_t(blockDim.x) + threadIdx.x, nt = gridDim.x * std::size_t(blockDim.x);
  for (int p = 0; p < passes; ++p) {
    const T* src = (p & 1) ? out : in;
    T* dst = (p & 1) ? const_cast<T*>(in) : out;
    for (std::size_t j = tid; j < n; j += nt) dst[j] = src[j] * T(0.999) + T(1e-3);
    grid.sync();
  }
}

/// An empty phase: what a kernel boundary costs when each CG phase is its own kernel.
__global__ void __launch_bounds__(kPcgMaxBlock) k_empty(int* sink) {
  if (blockIdx.x == 0 && threadIdx.x == 0 && sink[0] < 0) sink[0] = 0;
}

/// Writes a flag (to mapped host memory in the round-trip measurement).
__global__ void k_flag(int* p) {
  if (threadIdx.x == 0) *p = 1;
}

__global__ void __launch_bounds__(kPcgMaxBlock) k_sync_only(int syncs, int* sink) {
  coop::grid_group grid = coop::this_grid();
  for (int s = 0; s < syncs; ++s) grid.sync();
  if (blockIdx.x == 0 && threadIdx.x == 0) *sink = syncs;
}

/// Median of: launch a tiny kernel that writes 4 bytes of mapped host memory, synchronise.
double host_round_trip_us(cudaStream_t s, int* dev_scratch) {
  (void)dev_scratch;
  int* host = nullptr;
  int* dev = nullptr;
  CU(cudaHostAlloc(reinterpret_cast<void**>(&host), sizeof(int), cudaHostAllocMapped));
  CU(cudaHostGetDevicePointer(reinterpret_cast<void**>(&dev), host, 0));
  std::vector<double> rt;
  for (int rep = 0; rep < 101; ++rep) {
    const auto a0 = std::chrono::steady_clock::now();
    k_flag<<<1, 32, 0, s>>>(dev);
    CU(cudaPeekAtLastError());
    CU(cudaStreamSynchronize(s));
    rt.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - a0).count());
  }
  cudaFreeHost(host);
  std::sort(rt.begin(), rt.end());
  return rt[rt.size() / 2];
}

template <class T>
bool measure_floor(const Model& m, FloorEstimate& out) {
  const DeviceInfo& d = device_info();
  if (!d.ok) return false;
  const int nf = m.num_free(), nb = m.num_blocks(), ne = m.num_tets(), nn = m.num_nodes();
  const double S = sizeof(T);
  // One fused PCG iteration must read the matrix (values, column indices, row pointers)
  // and the block-Jacobi inverse once; phase A gathers z and p (each once, ideally),
  // writes p and q; phase B reads p, q, x, r and writes x, r, z: 11 vector passes.
  const double matrix = 9.0 * nb * S + 4.0 * nb + 4.0 * (nf + 1);
  const double vectors = 11.0 * 3.0 * nf * S + 9.0 * nf * S;
  // Where the rows live in registers the iterations do not read the matrix: it is read
  // once per step (counted with the step), and the floor of an iteration is its vectors.
  const PcgLaunch launch = pcg_launch<T>(nf, CudaTuning::from_environment());
  out.bytes_per_iteration = (launch.cached ? 0.0 : matrix) + vectors;
  out.syncs_per_iteration = 2;
  // Per step outside CG: the element pass (read tets, gradients, materials, quaternions and
  // each node's x and v once; write quaternions and one record per element), the assembly
  // (incidences, each element record and tet once, the matrix, preconditioner and
  // right-hand side written once) and the state update.
  const double elem = ne * (16.0 + 12 * S + 8 * S + 3 * S + kRec * S) + 2 * 3.0 * nn * S;
  const double assemble = ne * (4 * 4.0 + 16.0 + kRec * S) + 4.0 * nb + 9.0 * nb * S + 9.0 * nf * S + 3.0 * nf * S + 4.0 * nn * S;
  const double update = 3.0 * nf * S * 5;
  const double step_bytes = elem + assemble + update + (launch.cached ? matrix : 0.0);

  cudaStream_t s;
  CU(cudaStreamCreateWithFlags(&s, cudaStreamNonBlocking));
  const int grid = launch.grid;
  cudaEvent_t e0, e1;
  CU(cudaEventCreate(&e0));
  CU(cudaEventCreate(&e1));
  auto time_coop = [&](const void* fn, void** args, int g, int block) {
    std::vector<float> t;
    for (int rep = 0; rep < 7; ++rep) {
      CU(cudaEventRecord(e0, s));
      CU(cudaLaunchCooperativeKernel(fn, dim3(g), dim3(block), args, 0, s));
      CU(cudaEventRecord(e1, s));
      CU(cudaEventSynchronize(e1));
      float ms = 0;
      CU(cudaEventElapsedTime(&ms, e0, e1));
      t.push_back(ms);
    }
    std::sort(t.begin(), t.end());
    return double(t[t.size() / 2]);
  };
  // Barrier cost: a kernel of nothing but barriers, with the PCG's grid.
  DeviceArray<int> sink;
  sink.alloc(1);
  int syncs = 2000;
  int* sinkp = sink.get();
  void* sargs[] = {&syncs, &sinkp};
  const double t_sync = time_coop(reinterpret_cast<const void*>(&k_sync_only), sargs, grid, launch.block) * 1000.0 / syncs;
  // The alternatives to a grid barrier, measured once per process for docs/gpu-notes.md:
  // a kernel boundary in a stream and in a replayed CUDA graph, same grid.
  static std::once_flag said;
  std::call_once(said, [&] {
    constexpr int kLaunches = 200;
    auto time_stream = [&] {
      CU(cudaEventRecord(e0, s));
      for (int l = 0; l < kLaunches; ++l) k_empty<<<grid, launch.block, 0, s>>>(sinkp);
      CU(cudaPeekAtLastError());
      CU(cudaEventRecord(e1, s));
      CU(cudaEventSynchronize(e1));
      float ms = 0;
      CU(cudaEventElapsedTime(&ms, e0, e1));
      return ms * 1000.0 / kLaunches;
    };
    time_stream();
    const double t_stream = time_stream();
    cudaGraph_t g;
    cudaGraphExec_t ge;
    CU(cudaStreamBeginCapture(s, cudaStreamCaptureModeThreadLocal));
    for (int l = 0; l < kLaunches; ++l) k_empty<<<grid, launch.block, 0, s>>>(sinkp);
    CU(cudaStreamEndCapture(s, &g));
    CU(cudaGraphInstantiate(&ge, g, 0));
    CU(cudaGraphLaunch(ge, s));
    CU(cudaStreamSynchronize(s));
    std::vector<float> t;
    for (int rep = 0; rep < 5; ++rep) {
      CU(cudaEventRecord(e0, s));
      CU(cudaGraphLaunch(ge, s));
      CU(cudaEventRecord(e1, s));
      CU(cudaEventSynchronize(e1));
      float ms = 0;
      CU(cudaEventElapsedTime(&ms, e0, e1));
      t.push_back(ms);
    }
    std::sort(t.begin(), t.end());
    const double t_graph = t[t.size() / 2] * 1000.0 / kLaunches;
    cudaGraphExecDestroy(ge);
    cudaGraphDestroy(g);
    std::fprintf(stderr,
                 "cuda floor: %s, grid %d x %d%s: grid barrier %.2f us; kernel boundary %.2f us (stream), %.2f us "
                 "(graph replay); host round trip %.1f us (median)\n",
                 d.name.c_str(), grid, launch.block, launch.cached ? " (rows in registers)" : "", t_sync, t_stream, t_graph,
                 host_round_trip_us(s, sinkp));
  });
  // Bandwidth at the iteration's working-set size: passes that read and write it.
  std::size_t n = std::max<std::size_t>(1024, std::size_t(out.bytes_per_iteration / (2 * S)));
  DeviceArray<T> a, b;
  a.alloc(n);
  b.alloc(n);
  a.zero(s);
  b.zero(s);
  int passes = 200;
  T* ap = a.get();
  T* bp = b.get();
  void* bargs[] = {&ap, &bp, &n, &passes};
  int sgrid = 0;
  CU(cudaOccupancyMaxActiveBlocksPerMultiprocessor(&sgrid, k_stream_passes<T>, kBlock, 0));
  sgrid = std::max(1, sgrid) * d.sms;
  const double t_pass = time_coop(reinterpret_cast<const void*>(&k_stream_passes<T>), bargs, sgrid, kBlock) * 1000.0 / passes;
  // Sync cost of the stream kernel's own (full) grid, to subtract.
  void* sargs2[] = {&syncs, &sinkp};
  const double t_sync_full = time_coop(reinterpret_cast<const void*>(&k_sync_only), sargs2, sgrid, kBlock) * 1000.0 / syncs;
  const double moved = 2.0 * n * S;
  const double t_move = std::max(t_pass - t_sync_full, 0.05);
  out.bandwidth_gbs = moved / (t_move * 1e-6) / 1e9;
  out.sync_us = t_sync;
  out.iteration_us = out.bytes_per_iteration / (out.bandwidth_gbs * 1e3) + out.syncs_per_iteration * t_sync;
  // Step floor outside CG: its bytes at the same bandwidth (an optimistic figure where the
  // data does not fit in L2), the dependent phases that need a grid-wide barrier (element,
  // assembly, two in the PCG set-up, update, rest rule, finger sums: 7), and one host
  // round trip (a synchronous step() must launch and wait at least once).
  out.step_fixed_us = step_bytes / (out.bandwidth_gbs * 1e3) + 7 * t_sync + host_round_trip_us(s, sinkp);
  out.device = d.name;
  cudaEventDestroy(e0);
  cudaEventDestroy(e1);
  CU(cudaStreamSynchronize(s));
  cudaStreamDestroy(s);
  return true;
}

}  // namespace

}  // namespace cuda

bool cuda_measure_floor(const Model& model, Precision precision, FloorEstimate& out) {
  try {
    return precision == Precision::Float ? cuda::measure_floor<float>(model, out)
                                          : cuda::measure_floor<double>(model, out);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cuda floor: %s\n", e.what());
    return false;
  }
}

}  // namespace palpation::sim
