#include "socket_io.hpp"

#ifdef _WIN32
#include <winsock2.h>
#include <ws2tcpip.h>
#else
#include <netdb.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>
#endif

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <string>

namespace mocaplink::web::detail {

#ifdef _WIN32
static_assert(sizeof(Socket) == sizeof(SOCKET));

namespace {
SOCKET native(Socket socket) {
  return static_cast<SOCKET>(socket);
}
}  // namespace

SocketWait wait_socket(Socket socket, bool for_write, std::chrono::milliseconds timeout) {
  WSAPOLLFD entry{};
  entry.fd = native(socket);
  entry.events = for_write ? POLLOUT : POLLIN;
  const int ready = ::WSAPoll(&entry, 1, static_cast<INT>(timeout.count()));
  if (ready == 0) return SocketWait::timeout;
  if (ready < 0 || (entry.revents & POLLNVAL) != 0) return SocketWait::error;
  return SocketWait::ready;
}

ssize_t receive_bytes(Socket socket, char* data, std::size_t size) {
  return ::recv(native(socket), data, static_cast<int>(size), 0);
}

ssize_t send_bytes(Socket socket, const char* data, std::size_t size) {
  return ::send(native(socket), data, static_cast<int>(size), 0);  // Winsock raises no SIGPIPE
}

bool peer_is_open(Socket socket) {
  if (wait_socket(socket, false, std::chrono::milliseconds(0)) == SocketWait::timeout) return true;
  char byte = 0;  // readable: the peek returns at once
  return ::recv(native(socket), &byte, 1, MSG_PEEK) > 0;
}

std::string socket_address(Socket socket, bool local, int* port) {
  sockaddr_storage address{};
  int length = sizeof address;
  auto* raw = reinterpret_cast<sockaddr*>(&address);
  if ((local ? ::getsockname(native(socket), raw, &length)
             : ::getpeername(native(socket), raw, &length)) != 0) {
    return "";
  }
  char host[NI_MAXHOST] = {};
  char service[NI_MAXSERV] = {};
  if (::getnameinfo(raw, static_cast<socklen_t>(length), host, sizeof host, service, sizeof service,
                    NI_NUMERICHOST | NI_NUMERICSERV) != 0) {
    return "";
  }
  if (port != nullptr) *port = std::atoi(service);
  return host;
}

void close_connection(Socket socket) {
  ::shutdown(native(socket), SD_BOTH);
  ::closesocket(native(socket));
}

void set_listen_options(Socket socket) {
  const BOOL yes = TRUE;
  ::setsockopt(native(socket), SOL_SOCKET, SO_EXCLUSIVEADDRUSE, reinterpret_cast<const char*>(&yes),
               sizeof yes);
}

void raise_backlog(Socket socket) {
  ::listen(native(socket), SOMAXCONN);
}

std::string last_socket_error() {
  const int error = ::WSAGetLastError();
  if (error == 0) return "";
  char text[512] = {};
  const DWORD n =
      ::FormatMessageA(FORMAT_MESSAGE_FROM_SYSTEM | FORMAT_MESSAGE_IGNORE_INSERTS, nullptr,
                       static_cast<DWORD>(error), 0, text, sizeof text, nullptr);
  std::string message(text, n);
  while (!message.empty() && (message.back() == '\n' || message.back() == '\r' ||
                              message.back() == ' ' || message.back() == '.')) {
    message.pop_back();
  }
  return (message.empty() ? "socket error" : message) + " (WSA error " + std::to_string(error) +
         ")";
}

void clear_socket_error() {
  ::WSASetLastError(0);
}

#else

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

void set_listen_options(Socket socket) {
  const int yes = 1;
  ::setsockopt(socket, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
}

void raise_backlog(Socket socket) {
  ::listen(socket, SOMAXCONN);
}

std::string last_socket_error() {
  return errno == 0 ? std::string() : std::strerror(errno);
}

void clear_socket_error() {
  errno = 0;
}
#endif

}  // namespace mocaplink::web::detail
