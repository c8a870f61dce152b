#include "socket_io.hpp"

#include <netdb.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>

namespace mocaplink::web::detail {

SocketWait wait_socket(Socket socket, bool for_write, std::chrono::milliseconds timeout) {
  pollfd entry{};
  entry.fd = socket;
  entry.events = for_write ? POLLOUT : POLLIN;
  int ready = 0;
  do {
    ready = ::poll(&entry, 1, static_cast<int>(timeout.count()));
  } while (ready < 0 && errno == EINTR);
  if (ready == 0) return SocketWait::timeout;
  if (ready < 0 || (entry.revents & POLLNVAL) != 0) return SocketWait::error;
  // A hang-up still reads as end of stream; an error shows on the next call.
  return SocketWait::ready;
}

ssize_t receive_bytes(Socket socket, char* data, std::size_t size) {
  ssize_t n = 0;
  do {
    n = ::recv(socket, data, size, 0);
  } while (n < 0 && errno == EINTR);
  return n;
}

ssize_t send_bytes(Socket socket, const char* data, std::size_t size) {
  ssize_t n = 0;
  do {
    n = ::send(socket, data, size, MSG_NOSIGNAL);
  } while (n < 0 && errno == EINTR);
  return n;
}

bool peer_is_open(Socket socket) {
  pollfd entry{};
  entry.fd = socket;
  entry.events = POLLIN;
  const int ready = ::poll(&entry, 1, 0);
  if (ready == 0) return true;
  if (ready < 0 || (entry.revents & POLLNVAL) != 0) return false;
  char byte = 0;
  return ::recv(socket, &byte, 1, MSG_PEEK | MSG_DONTWAIT) > 0;
}

std::string socket_address(Socket socket, bool local, int* port) {
  sockaddr_storage address{};
  socklen_t length = sizeof address;
  auto* raw = reinterpret_cast<sockaddr*>(&address);
  if ((local ? ::getsockname(socket, raw, &length) : ::getpeername(socket, raw, &length)) != 0) {
    return "";
  }
  char host[NI_MAXHOST] = {};
  char service[NI_MAXSERV] = {};
  if (::getnameinfo(raw, length, host, sizeof host, service, sizeof service,
                    NI_NUMERICHOST | NI_NUMERICSERV) != 0) {
    return "";
  }
  if (port != nullptr) *port = std::atoi(service);
  return host;
}

void close_connection(Socket socket) {
  ::shutdown(socket, SHUT_RDWR);
  ::close(socket);
}

}  // namespace mocaplink::web::detail
