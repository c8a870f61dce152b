// The few socket calls the dashboard server makes itself, beyond cpp-httplib (request_stream.hpp):
// waiting for a socket, reading, writing, the peer's address, closing, and the listening socket's
// options. Every platform difference of the server is here: POSIX (poll, recv/send, close) and
// Winsock (WSAPoll, recv/send, closesocket).
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>

#include <sys/types.h>

namespace mocaplink::web::detail {

/// The socket type cpp-httplib hands the server (int on POSIX, SOCKET on Windows).
#ifdef _WIN32
using Socket = std::uintptr_t;
#else
using Socket = int;
#endif

enum class SocketWait {
  ready,    ///< readable (data or end of stream) / writable
  timeout,  ///< nothing within the time given
  error,    ///< poll failed or the socket is in error
};

/// Waits up to `timeout` (≥ 0) until `socket` is readable, or writable when `for_write`.
[[nodiscard]] SocketWait wait_socket(Socket socket, bool for_write,
                                     std::chrono::milliseconds timeout);

/// recv / send without SIGPIPE; the POSIX return value (bytes, 0 = end of stream, −1 = error).
ssize_t receive_bytes(Socket socket, char* data, std::size_t size);
ssize_t send_bytes(Socket socket, const char* data, std::size_t size);

/// False once the peer has closed its side (end of stream pending) or the socket is gone.
[[nodiscard]] bool peer_is_open(Socket socket);

/// The numeric address (no port) of the peer, or of this end when `local`; "" when unknown.
[[nodiscard]] std::string socket_address(Socket socket, bool local, int* port = nullptr);

/// Shuts both directions down and closes `socket`.
void close_connection(Socket socket);

/// Options of the listening socket, set before bind. Linux: SO_REUSEADDR only (httplib's default
/// SO_REUSEPORT would let a second daemon bind the same port and take half the requests);
/// Windows: SO_EXCLUSIVEADDRUSE (its SO_REUSEADDR would let another program take the port).
void set_listen_options(Socket socket);

/// Raises the backlog of the bound, listening socket to SOMAXCONN.
void raise_backlog(Socket socket);

/// The reason of the last failed socket call on this thread ("" when none is recorded), and
/// clearing it before a call.
[[nodiscard]] std::string last_socket_error();
void clear_socket_error();

}  // namespace mocaplink::web::detail
