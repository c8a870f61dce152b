// serial:///dev/ttyX?baud=N (Linux) or serial://COM3?baud=N (Windows) — a telemetry radio, a USB
// cable to the flight controller, a UART on a companion computer. The port is put in raw mode
// (cfmakeraw: 8 data bits, no parity, 1 stop bit, no echo, no line editing, no CR/LF translation,
// no software flow control) at the configured baud rate. A device that is missing or disappears
// (USB unplugged) is reopened with back-off (link_stream.hpp). A telemetry radio's bandwidth is the
// usual bottleneck: the run command warns when a vehicle's message profile needs more than baud/10
// bytes per second (8N1 = 10 bits/byte).
#pragma once

#include <cstdint>
#include <string>

#include <asio/serial_port.hpp>

#include "mocaplink/io/link_stream.hpp"

namespace mocaplink::io {

class SerialLink final : public StreamLink {
 public:
  /// `device`: absolute path (/dev/ttyUSB0, /dev/serial/by-id/...) or, on Windows, a COM port name
  /// (COM3); `baud`: one of the rates libs/config accepts.
  SerialLink(asio::io_context& loop, std::string device, std::uint32_t baud, LinkOptions options);
  ~SerialLink() override;

  [[nodiscard]] std::string url() const override;

 private:
  void async_open(OpenHandler done) override;
  void async_write_all(std::span<const std::uint8_t> bytes, IoHandler done) override;
  void async_read_some(std::span<std::uint8_t> buffer, IoHandler done) override;
  void close_transport() noexcept override;
  [[nodiscard]] std::optional<std::size_t> unsent_bytes() const noexcept override;

  std::string device_;
  std::uint32_t baud_;
  asio::serial_port port_;
};

}  // namespace mocaplink::io
