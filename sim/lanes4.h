// Four-lane vectors of T (GCC/Clang vector extensions: no intrinsics, any target; with
// -march=x86-64-v3 a float vector is one SSE register and a double one AVX register) for
// the CPU backend's 3-vectors and 3x3 columns: lanes 0-2 hold x, y, z, lane 3 is 0 or
// ignored. Used where the scalar Eigen 3x3 code measured slow in the per-step passes
// (docs/benchmarks.md): the block product of CG and the element pass.
#pragma once

#include <cstdint>
#include <cstring>
#include <type_traits>

namespace palpation::sim::lanes {

template <class T>
struct Lanes4 {
  typedef T V4 __attribute__((vector_size(4 * sizeof(T))));
  using I = std::conditional_t<sizeof(T) == 4, std::int32_t, std::int64_t>;
  typedef I Mask __attribute__((vector_size(4 * sizeof(T))));
};

template <class T>
using V4 = typename Lanes4<T>::V4;

/// Four values from p (unaligned).
template <class T>
inline V4<T> load4(const T* p) {
  V4<T> v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

/// Three values from p, lane 3 zero (does not read past p[2]).
template <class T>
inline V4<T> load3(const T* p) {
  return V4<T>{p[0], p[1], p[2], T(0)};
}

template <class T>
inline void store4(T* p, V4<T> v) {
  std::memcpy(p, &v, sizeof v);
}

/// M y for a 3x3 M given by its columns.
template <class T>
inline V4<T> mul(const V4<T> c[3], V4<T> y) {
  return c[0] * y[0] + c[1] * y[1] + c[2] * y[2];
}

/// Adds the 3x3 block given by its columns to the nine column-major values at dst,
/// writing only those nine (two four-lane adds and one scalar).
template <class T>
inline void add_block(T* dst, const V4<T> c[3]) {
  // Lanes of two vectors (index 4 and up: the second), by each compiler's own builtin.
#if defined(__clang__)
  store4(dst, load4(dst) + __builtin_shufflevector(c[0], c[1], 0, 1, 2, 4));
  store4(dst + 4, load4(dst + 4) + __builtin_shufflevector(c[1], c[2], 1, 2, 4, 5));
#else
  using Mask = typename Lanes4<T>::Mask;
  store4(dst, load4(dst) + __builtin_shuffle(c[0], c[1], Mask{0, 1, 2, 4}));
  store4(dst + 4, load4(dst + 4) + __builtin_shuffle(c[1], c[2], Mask{1, 2, 4, 5}));
#endif
  dst[8] += c[2][2];
}

}  // namespace palpation::sim::lanes
