// One request on a dashboard connection, as the cpp-httplib stream the server reads it from and
// writes its answer to: reads wait at most the RequestDeadline allows (the silence limit between
// bytes, and the whole request's deadline from its first byte), so a client that sends slowly or
// stops halfway is cut off (timed_out()). Writes (the answer, an event stream) are bounded by the
// write timeout only. One thread uses a stream; it does not own the socket.
#pragma once

#include <array>
#include <chrono>

#include <httplib.h>

#include "mocaplink/web/connection_limits.hpp"
#include "socket_io.hpp"

namespace mocaplink::web::detail {

class RequestStream final : public httplib::Stream {
 public:
  /// `deadline` already started (the request's first byte is waiting on `socket`).
  RequestStream(Socket socket, RequestDeadline deadline, std::chrono::milliseconds write_timeout)
      : socket_(socket), deadline_(deadline), write_timeout_(write_timeout) {}

  bool is_readable() const override;
  bool is_writable() const override;
  ssize_t read(char* ptr, size_t size) override;
  ssize_t write(const char* ptr, size_t size) override;
  void get_remote_ip_and_port(std::string& ip, int& port) const override;
  void get_local_ip_and_port(std::string& ip, int& port) const override;
  socket_t socket() const override { return socket_; }

  /// The request did not arrive in time: reads failed and writes are refused since. The server
  /// then answers 408 itself (answer_timed_out()) and closes the connection.
  [[nodiscard]] bool timed_out() const { return timed_out_; }
  /// Sends "408 Request Timeout" (Connection: close) on the socket, once the stream timed out.
  void answer_timed_out();

 private:
  Socket socket_;
  RequestDeadline deadline_;
  std::chrono::milliseconds write_timeout_;
  bool timed_out_ = false;
  // httplib reads the request line and headers one byte at a time: read ahead from the socket.
  std::array<char, 4096> buffer_{};
  std::size_t buffered_begin_ = 0;
  std::size_t buffered_end_ = 0;
};

}  // namespace mocaplink::web::detail
