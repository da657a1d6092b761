// Lock-free single-producer / single-consumer ring of fixed capacity (allocated once, at
// construction, before the threads start). push() never blocks: when full it drops the
// value and counts it, so the 1 kHz producer never waits for a slow consumer.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>

namespace palpation::device {

template <class T>
class SpscRing {
 public:
  explicit SpscRing(std::size_t capacity) : cap_(capacity + 1), buf_(std::make_unique<T[]>(capacity + 1)) {}
  SpscRing(const SpscRing&) = delete;
  SpscRing& operator=(const SpscRing&) = delete;

  /// Producer. False (and counted in dropped()) when the ring is full.
  bool push(const T& v) {
    const std::size_t h = head_.load(std::memory_order_relaxed);
    const std::size_t next = h + 1 == cap_ ? 0 : h + 1;
    if (next == tail_.load(std::memory_order_acquire)) {
      dropped_.fetch_add(1, std::memory_order_relaxed);
      return false;
    }
    buf_[h] = v;
    head_.store(next, std::memory_order_release);
    return true;
  }
  /// Consumer. False when empty.
  bool pop(T& v) {
    const std::size_t t = tail_.load(std::memory_order_relaxed);
    if (t == head_.load(std::memory_order_acquire)) return false;
    v = buf_[t];
    tail_.store(t + 1 == cap_ ? 0 : t + 1, std::memory_order_release);
    return true;
  }
  std::size_t capacity() const { return cap_ - 1; }
  std::uint64_t dropped() const { return dropped_.load(std::memory_order_relaxed); }

 private:
  const std::size_t cap_;
  std::unique_ptr<T[]> buf_;
  alignas(64) std::atomic<std::size_t> head_{0};
  alignas(64) std::atomic<std::size_t> tail_{0};
  alignas(64) std::atomic<std::uint64_t> dropped_{0};
};

}  // namespace palpation::device
