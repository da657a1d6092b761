// Lock-free single-producer / single-consumer triple buffer: the producer always has a
// slot to write, the consumer always reads the newest complete value, neither waits.
// Hand-off by one atomic exchange with acquire/release ordering (design.md section 3).
#pragma once

#include <atomic>
#include <cstdint>

namespace palpation::device {

template <class T>
class TripleBuffer {
 public:
  TripleBuffer() = default;
  explicit TripleBuffer(const T& init) {
    for (auto& s : slots_) s = init;
  }
  TripleBuffer(const TripleBuffer&) = delete;
  TripleBuffer& operator=(const TripleBuffer&) = delete;

  /// Producer: the slot to fill, then publish().
  T& write_slot() { return slots_[back_]; }
  void publish() {
    // Release: the slot's contents happen-before the consumer's acquire of this index.
    const std::uint8_t old = middle_.exchange(std::uint8_t(back_ | kFresh), std::memory_order_acq_rel);
    back_ = old & kIndex;
  }
  void publish(const T& value) {
    write_slot() = value;
    publish();
  }

  /// Consumer: takes the newest published value if there is one. Returns true when it
  /// changed since the last call; `read()` is then the newest.
  bool update() {
    if (!(middle_.load(std::memory_order_relaxed) & kFresh)) return false;
    const std::uint8_t old = middle_.exchange(front_, std::memory_order_acq_rel);
    front_ = old & kIndex;
    return true;
  }
  const T& read() const { return slots_[front_]; }

 private:
  static constexpr std::uint8_t kIndex = 3, kFresh = 4;
  // Separate cache lines: the two threads write back_/front_ only.
  alignas(64) T slots_[3]{};
  alignas(64) std::atomic<std::uint8_t> middle_{1};
  alignas(64) std::uint8_t back_ = 0;
  alignas(64) std::uint8_t front_ = 2;
};

}  // namespace palpation::device
