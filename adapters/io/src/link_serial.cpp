#include "mocaplink/io/link_serial.hpp"

#include "unsent.hpp"

#ifndef _WIN32
#include <termios.h>
#endif

#include <cerrno>
#include <utility>

#include <asio/post.hpp>
#include <asio/write.hpp>

namespace mocaplink::io {
namespace {

#ifdef _WIN32
/// Windows: asio's DCB settings (binary mode, the options below) and its COMMTIMEOUTS (a read
/// returns as soon as one byte is there) are already the raw mode. `device` is a name like COM3
/// (asio adds the \\.\ prefix that COM10 and above need).
std::error_code make_raw(asio::serial_port::native_handle_type /*handle*/) {
  return {};
}
#else
/// Raw mode on top of what asio sets: cfmakeraw also clears the remaining input processing
/// flags, and VMIN=1/VTIME=0 makes reads return as soon as one byte is there.
std::error_code make_raw(int fd) {
  termios tio{};
  if (::tcgetattr(fd, &tio) != 0) return {errno, std::generic_category()};
  ::cfmakeraw(&tio);
  tio.c_cflag |= CLOCAL | CREAD;
  tio.c_cc[VMIN] = 1;
  tio.c_cc[VTIME] = 0;
  if (::tcsetattr(fd, TCSANOW, &tio) != 0) return {errno, std::generic_category()};
  return {};
}
#endif

}  // namespace

SerialLink::SerialLink(asio::io_context& loop, std::string device, std::uint32_t baud,
                       LinkOptions options)
    : StreamLink(loop, std::move(options), static_cast<double>(baud) / 10.0),  // 8N1: 10 bits
      device_(std::move(device)),
      baud_(baud),
      port_(loop) {}

SerialLink::~SerialLink() {
  close_transport();
}

std::string SerialLink::url() const {
  return "serial://" + device_ + "?baud=" + std::to_string(baud_);
}

void SerialLink::async_open(OpenHandler done) {
  std::error_code ec;
  close_transport();
  port_.open(device_, ec);
  if (!ec) ec = make_raw(port_.native_handle());
  if (!ec) port_.set_option(asio::serial_port_base::baud_rate(baud_), ec);
  if (!ec) port_.set_option(asio::serial_port_base::character_size(8), ec);
  if (!ec) {
    port_.set_option(asio::serial_port_base::parity(asio::serial_port_base::parity::none), ec);
  }
  if (!ec) {
    port_.set_option(asio::serial_port_base::stop_bits(asio::serial_port_base::stop_bits::one), ec);
  }
  if (!ec) {
    port_.set_option(
        asio::serial_port_base::flow_control(asio::serial_port_base::flow_control::none), ec);
  }
  std::string detail = ec ? "cannot open " + url() : "opened " + url();
  asio::post(loop_, [done = std::move(done), ec, detail = std::move(detail)] { done(ec, detail); });
}

void SerialLink::async_write_all(std::span<const std::uint8_t> bytes, IoHandler done) {
  asio::async_write(port_, asio::buffer(bytes.data(), bytes.size()), std::move(done));
}

void SerialLink::async_read_some(std::span<std::uint8_t> buffer, IoHandler done) {
  port_.async_read_some(asio::buffer(buffer.data(), buffer.size()), std::move(done));
}

void SerialLink::close_transport() noexcept {
  std::error_code ignored;
  port_.close(ignored);
}

std::optional<std::size_t> SerialLink::unsent_bytes() const noexcept {
  if (!port_.is_open()) return std::nullopt;
  return detail::unsent_bytes(const_cast<decltype(port_)&>(port_).native_handle());
}

}  // namespace mocaplink::io
