#include "request_stream.hpp"

#include <algorithm>
#include <cstring>
#include <string_view>

namespace mocaplink::web::detail {

bool RequestStream::is_readable() const {
  if (buffered_begin_ < buffered_end_) return true;
  const auto wait = deadline_.next_wait(RequestDeadline::Clock::now());
  return wait && wait_socket(socket_, false, *wait) == SocketWait::ready;
}

bool RequestStream::is_writable() const {
  return !timed_out_ && wait_socket(socket_, true, write_timeout_) == SocketWait::ready &&
         peer_is_open(socket_);
}

ssize_t RequestStream::read(char* ptr, size_t size) {
  if (buffered_begin_ == buffered_end_) {
    if (timed_out_) return -1;
    const auto wait = deadline_.next_wait(RequestDeadline::Clock::now());
    const SocketWait ready = wait ? wait_socket(socket_, false, *wait) : SocketWait::timeout;
    if (ready != SocketWait::ready) {
      timed_out_ = ready == SocketWait::timeout;
      return -1;
    }
    const ssize_t n = receive_bytes(socket_, buffer_.data(), buffer_.size());
    if (n <= 0) return n;
    buffered_begin_ = 0;
    buffered_end_ = static_cast<std::size_t>(n);
  }
  const std::size_t count = std::min(size, buffered_end_ - buffered_begin_);
  std::memcpy(ptr, buffer_.data() + buffered_begin_, count);
  buffered_begin_ += count;
  return static_cast<ssize_t>(count);
}

ssize_t RequestStream::write(const char* ptr, size_t size) {
  if (!is_writable()) return -1;
  return send_bytes(socket_, ptr, size);
}

void RequestStream::get_remote_ip_and_port(std::string& ip, int& port) const {
  ip = socket_address(socket_, false, &port);
}

void RequestStream::get_local_ip_and_port(std::string& ip, int& port) const {
  ip = socket_address(socket_, true, &port);
}

void RequestStream::answer_timed_out() {
  constexpr std::string_view kAnswer =
      "HTTP/1.1 408 Request Timeout\r\nConnection: close\r\nContent-Type: text/plain\r\n"
      "Content-Length: 36\r\n\r\nthe request took too long to arrive\n";
  static_assert(std::string_view("the request took too long to arrive\n").size() == 36);
  if (timed_out_ && wait_socket(socket_, true, write_timeout_) == SocketWait::ready) {
    (void)send_bytes(socket_, kAnswer.data(), kAnswer.size());
  }
}

}  // namespace mocaplink::web::detail
