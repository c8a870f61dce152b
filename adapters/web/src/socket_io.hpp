// The few socket calls the dashboard server makes itself, beyond cpp-httplib (request_stream.hpp):
// waiting for a socket, reading, writing, the peer's address and closing. POSIX only, and kept
// here on purpose: a Windows build replaces this one file (WSAPoll, recv/send, closesocket).
#pragma once

#include <chrono>
#include <cstddef>
#include <string>

#include <sys/types.h>

namespace mocaplink::web::detail {

/// The socket type cpp-httplib hands the server (int on POSIX).
using Socket = int;

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

}  // namespace mocaplink::web::detail
