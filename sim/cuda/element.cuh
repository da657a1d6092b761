// Element stage of the CUDA backends: per element, the deformation gradient, the rotation
// (warm-started quaternion, fem_corotational.h line for line), r_a = R g_a and the
// element's right-hand-side matrix Q, written as one compact record that the assembly
// (assembly.cu) gathers. The same launch runs the start-of-step contact detection in extra
// blocks (contact.cuh).
#pragma once

#include "cuda/common.cuh"
#include "cuda/contact.cuh"

namespace palpation::sim::cuda {

// Element record (kRec T): r_a = R g_a (12), V lambda, V mu, and Q (6: xx xy xz yy yz zz),
// the symmetric matrix with which the element adds Q r_a to the right-hand side of node a:
//   h (f_a - (beta + h) (K v)_a) = -h V (R S R^T + (beta + h) Sv) r_a = Q r_a,
// since f_a = -V R S g_a = -V (R S R^T) r_a and (K v)_a = V Sv r_a (fem_corotational.h).
constexpr int kRec = 20;
constexpr int kElemBlock = 128;

template <class T>
struct ElementArgs {
  int ne;
  const int4* tets;
  const T* grad;    // (ne x 12) g_0..g_3
  const T* vol;     // (ne)
  const T* lambda;  // (ne)
  const T* mu;      // (ne)
  T* quat;          // (ne x 4) w x y z
  const T* x;
  const T* v;
  T* rec;           // (ne x kRec)
  T h, beta;
  int elem_blocks;  // blocks [0, elem_blocks) do elements, the others detect contacts; set by launch_element
  T* rest_part = nullptr;  // (ne) (V / 4) (tr R - 3), for the nodal-pressure term (pressure.cuh); none: not written
};

/// Launches k_element in stream s: ceil(ne / kElemBlock) blocks of elements, plus, when
/// `detect`, ceil(ntri / kElemBlock) (at least one) blocks of start-of-step detection.
template <class T>
void launch_element(cudaStream_t s, ElementArgs<T> a, const DetectArgs<T>& d, const FingersArg& F, const StepConsts& k,
                    bool detect);

}  // namespace palpation::sim::cuda
