// A non-blocking IPv4 UDP socket (POSIX). Sends and receives never block, so the 1 kHz
// loops can call them every tick; nothing here allocates after open().
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace palpation::device {

/// An IPv4 address and port, both in host order.
struct Endpoint {
  std::uint32_t address = 0;   // e.g. 0x7F000001 for 127.0.0.1
  std::uint16_t port = 0;
  bool valid() const { return port != 0; }
  friend bool operator==(const Endpoint&, const Endpoint&) = default;
};

/// Parses "a.b.c.d" (no name lookup: the robot is addressed by number). False on error.
bool parse_ipv4(const std::string& text, std::uint32_t& address);
std::string to_string(const Endpoint& e);

class UdpSocket {
 public:
  UdpSocket() = default;
  ~UdpSocket();
  UdpSocket(const UdpSocket&) = delete;
  UdpSocket& operator=(const UdpSocket&) = delete;
  UdpSocket(UdpSocket&& o) noexcept;
  UdpSocket& operator=(UdpSocket&& o) noexcept;

  /// Binds to address:port (port 0: the system picks one; see local_port()). On failure
  /// returns false with a reason in `error`.
  bool open(const std::string& bind_address, std::uint16_t port, std::string* error = nullptr);
  void close();
  bool is_open() const { return fd_ >= 0; }
  std::uint16_t local_port() const { return port_; }

  /// Sends one datagram. False when the kernel refused it (buffer full, no route).
  bool send_to(const Endpoint& to, const std::uint8_t* data, std::size_t size);
  /// Receives one datagram if one is waiting: returns its size (it may be truncated to
  /// `capacity`: then `truncated` is set), or -1 when none is waiting.
  long receive(std::uint8_t* buffer, std::size_t capacity, Endpoint* from = nullptr, bool* truncated = nullptr);
  /// Waits up to timeout_ms for a datagram (tests and the emulator's idle wait). True when
  /// one is ready.
  bool wait_readable(int timeout_ms);

 private:
  int fd_ = -1;
  std::uint16_t port_ = 0;
};

}  // namespace palpation::device
