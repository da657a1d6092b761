#include "udp_socket.h"

#include <arpa/inet.h>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

namespace palpation::device {

bool parse_ipv4(const std::string& text, std::uint32_t& address) {
  in_addr a{};
  if (::inet_pton(AF_INET, text.c_str(), &a) != 1) return false;
  address = ntohl(a.s_addr);
  return true;
}

std::string to_string(const Endpoint& e) {
  return std::to_string((e.address >> 24) & 255) + "." + std::to_string((e.address >> 16) & 255) + "." +
         std::to_string((e.address >> 8) & 255) + "." + std::to_string(e.address & 255) + ":" + std::to_string(e.port);
}

UdpSocket::~UdpSocket() { close(); }

UdpSocket::UdpSocket(UdpSocket&& o) noexcept : fd_(o.fd_), port_(o.port_) { o.fd_ = -1; }

UdpSocket& UdpSocket::operator=(UdpSocket&& o) noexcept {
  if (this != &o) {
    close();
    fd_ = o.fd_;
    port_ = o.port_;
    o.fd_ = -1;
  }
  return *this;
}

bool UdpSocket::open(const std::string& bind_address, std::uint16_t port, std::string* error) {
  close();
  auto fail = [&](const std::string& what) {
    if (error) *error = what + " (" + std::strerror(errno) + ")";
    close();
    return false;
  };
  std::uint32_t addr = 0;
  if (!parse_ipv4(bind_address, addr)) {
    if (error) *error = "\"" + bind_address + "\" is not an IPv4 address";
    return false;
  }
  fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd_ < 0) return fail("socket");
  sockaddr_in sa{};
  sa.sin_family = AF_INET;
  sa.sin_port = htons(port);
  sa.sin_addr.s_addr = htonl(addr);
  if (::bind(fd_, reinterpret_cast<const sockaddr*>(&sa), sizeof sa) != 0)
    return fail("bind " + bind_address + ":" + std::to_string(port));
  socklen_t len = sizeof sa;
  if (::getsockname(fd_, reinterpret_cast<sockaddr*>(&sa), &len) != 0) return fail("getsockname");
  port_ = ntohs(sa.sin_port);
  return true;
}

void UdpSocket::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  port_ = 0;
}

bool UdpSocket::send_to(const Endpoint& to, const std::uint8_t* data, std::size_t size) {
  if (fd_ < 0) return false;
  sockaddr_in sa{};
  sa.sin_family = AF_INET;
  sa.sin_port = htons(to.port);
  sa.sin_addr.s_addr = htonl(to.address);
  const ssize_t n = ::sendto(fd_, data, size, MSG_DONTWAIT | MSG_NOSIGNAL, reinterpret_cast<const sockaddr*>(&sa), sizeof sa);
  return n == static_cast<ssize_t>(size);
}

long UdpSocket::receive(std::uint8_t* buffer, std::size_t capacity, Endpoint* from, bool* truncated) {
  if (fd_ < 0) return -1;
  sockaddr_in sa{};
  socklen_t len = sizeof sa;
  for (;;) {
    const ssize_t n = ::recvfrom(fd_, buffer, capacity, MSG_DONTWAIT | MSG_TRUNC, reinterpret_cast<sockaddr*>(&sa), &len);
    if (n < 0) {
      if (errno == EINTR) continue;
      // EAGAIN: nothing waiting. ECONNREFUSED (an ICMP error from an earlier send): skip.
      if (errno == ECONNREFUSED) continue;
      return -1;
    }
    if (from) *from = Endpoint{ntohl(sa.sin_addr.s_addr), ntohs(sa.sin_port)};
    if (truncated) *truncated = static_cast<std::size_t>(n) > capacity;
    return static_cast<long>(n);
  }
}

bool UdpSocket::wait_readable(int timeout_ms) {
  if (fd_ < 0) return false;
  pollfd p{fd_, POLLIN, 0};
  return ::poll(&p, 1, timeout_ms) > 0 && (p.revents & POLLIN);
}

}  // namespace palpation::device
