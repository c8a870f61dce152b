// Raw TCP clients for the connection tests: they connect from a chosen loopback address (all of
// 127.0.0.0/8 is loopback on Linux), send what a test says and no more, and read what comes back.
#pragma once

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <cstdint>
#include <string>

namespace mocaplink::web::testing {

/// A TCP connection to 127.0.0.1:`port` from `from` (a 127.x.y.z address) that sends `text` and
/// then nothing more; -1 on failure.
inline int connect_and_send(std::uint16_t port, const std::string& text,
                            const char* from = "127.0.0.1") {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) return -1;
  sockaddr_in local{};
  local.sin_family = AF_INET;
  ::inet_pton(AF_INET, from, &local.sin_addr);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(port);
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::bind(fd, reinterpret_cast<sockaddr*>(&local), sizeof local) != 0 ||
      ::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 ||
      (!text.empty() && ::send(fd, text.data(), text.size(), MSG_NOSIGNAL) < 0)) {
    ::close(fd);
    return -1;
  }
  return fd;
}

/// Everything the server sends on `fd` until it closes the connection (or `deadline_s` passes
/// without a byte: a generous bound so that a broken server fails the test instead of hanging it).
inline std::string read_until_closed(int fd, int deadline_s = 30) {
  timeval timeout{deadline_s, 0};
  ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  std::string received;
  char buffer[1024];
  while (true) {
    const ssize_t n = ::recv(fd, buffer, sizeof buffer, 0);
    if (n <= 0) return received;
    received.append(buffer, static_cast<std::size_t>(n));
  }
}

}  // namespace mocaplink::web::testing
