#include "mocaplink/sources/vicon_udp_sender.hpp"

#include <algorithm>
#include <chrono>
#include <vector>

#include <asio.hpp>

#include "mocaplink/sources/emulator_support.hpp"

namespace mocaplink::sources {

namespace vu = wire::vicon_udp;
using asio::ip::udp;

config::ValueOrError<ViconUdpSenderOptions> vicon_udp_sender_options(
    const EmulatorOptions& options) {
  using Result = config::ValueOrError<ViconUdpSenderOptions>;
  ViconUdpSenderOptions o;
  o.to_host = options.to_host;
  o.to_port = options.to_port;
  o.rate_hz = options.rate_hz;
  for (const auto& [key, value] : options.settings) {
    std::uint64_t n = 0;
    std::string error;
    if (key == "rotation") {
      if (value != "xyz" && value != "zyx") {
        error = "rotation must be xyz or zyx, got " + config::quote(value);
      }
      o.rotation = value == "zyx" ? vu::EulerOrder::zyx : vu::EulerOrder::xyz;
    } else if (key == "occluded") {
      if (value != "omit" && value != "zeros") {
        error = "occluded must be omit or zeros, got " + config::quote(value);
      }
      o.occluded_as_zeros = value == "zeros";
    } else if (key == "frame_step") {
      error = config::read_count_option(key, value, 1, 100, n);
      o.frame_step = static_cast<std::uint32_t>(n);
    } else if (key == "first_frame") {
      error = config::read_count_option(key, value, 0, 0xFFFF'FFFFu, n);
      o.first_frame = static_cast<std::uint32_t>(n);
    } else if (key == "per_datagram") {
      error = config::read_count_option(key, value, 1, 255, n);
      o.per_datagram = static_cast<std::size_t>(n);
    } else if (key == "block_size") {
      // One object item must fit (5 + 75 bytes), and a datagram is at most 65507 bytes.
      error = config::read_count_option(key, value, 0, vu::kMaxDatagramBytes, n);
      if (error.empty() && n != 0 && vu::objects_per_block(static_cast<std::size_t>(n)) == 0) {
        error = "block_size must be 0 (no padding) or 80 to 65507 (Tracker: 256, 512, 1024), got " +
                config::quote(value);
      }
      o.block_bytes = static_cast<std::size_t>(n);
    }
    if (!error.empty()) return Result::failure(error);  // each message ends with ", got …"
  }
  return o;
}

class ViconUdpSender::Impl {
 public:
  Impl(const ViconUdpSenderOptions& options, ViconUdpSenderCounters& counters,
       FrameProvider provider)
      : options_(options),
        counters_(counters),
        provider_(std::move(provider)),
        next_frame_(options.first_frame) {}

  std::optional<std::string> open() {
    asio::error_code ec;
    udp::resolver resolver(io_);
    const auto found =
        resolver.resolve(udp::v4(), options_.to_host, std::to_string(options_.to_port), ec);
    if (ec || found.empty()) return "cannot resolve " + options_.to_host + ": " + ec.message();
    to_ = *found.begin();
    if (socket_.open(to_.protocol(), ec); ec) return "socket: " + ec.message();
    if (socket_.bind(udp::endpoint(to_.protocol(), 0), ec); ec) return "bind: " + ec.message();
    return std::nullopt;
  }
  std::uint16_t local_port() const {
    asio::error_code ec;
    return socket_.local_endpoint(ec).port();
  }

  void run() {
    if (provider_) {
      schedule_.emplace(options_.rate_hz, std::chrono::steady_clock::now());
      next_tick();
    }
    auto guard = asio::make_work_guard(io_);
    io_.run();
    asio::error_code ignored;
    socket_.close(ignored);
  }

  void stop() { io_.stop(); }

  void publish(core::MocapFrame frame) {
    asio::post(io_, [this, f = std::move(frame)] { send(f); });
  }

 private:
  void next_tick() {
    timer_.expires_at(schedule_->due());
    timer_.async_wait([this](const asio::error_code& ec) {
      if (ec) return;
      // Frame numbers follow the schedule, as a Tracker's follow its cameras: a tick skipped
      // or without a frame is a missing number.
      next_frame_ = options_.first_frame +
                    static_cast<std::uint32_t>(schedule_->tick()) * options_.frame_step;
      if (auto frame = provider_(schedule_->tick())) send(*frame);
      schedule_->advance(std::chrono::steady_clock::now());
      next_tick();
    });
  }

  void send(const core::MocapFrame& frame) {
    ++counters_.frames;
    std::vector<vu::Object> objects;
    for (const auto& body : frame.bodies) {
      if (!body.tracked && !options_.occluded_as_zeros) continue;
      vu::Object o;
      o.name = body.name.substr(0, vu::kNameBytes);
      if (body.tracked) {
        o.t_mm = body.p_world_m * 1000.0;
        o.rot_rad = vu::to_euler(body.q_world_body, options_.rotation);
      }
      objects.push_back(std::move(o));
    }
    const std::uint32_t number = next_frame_;
    next_frame_ += options_.frame_step;  // wraps at 2^32 as the Vicon counter would
    // As many objects per datagram as the block holds; the rest in further blocks with the same
    // frame number.
    const std::size_t per_datagram =
        std::min(options_.per_datagram, vu::objects_per_block(options_.block_bytes));
    std::size_t first = 0;
    do {
      const std::size_t n = std::min(per_datagram, objects.size() - first);
      const auto datagram = vu::encode_datagram(
          number, std::span<const vu::Object>(objects.data() + first, n), options_.block_bytes);
      asio::error_code ec;
      socket_.send_to(asio::buffer(datagram), to_, 0, ec);
      ++(ec ? counters_.send_errors : counters_.datagrams);
      first += n;
    } while (first < objects.size());
  }

  const ViconUdpSenderOptions& options_;
  ViconUdpSenderCounters& counters_;
  asio::io_context io_;
  udp::socket socket_{io_};
  udp::endpoint to_;
  asio::steady_timer timer_{io_};
  FrameProvider provider_;
  std::optional<TickSchedule> schedule_;
  std::uint32_t next_frame_;
};

ViconUdpSender::ViconUdpSender(ViconUdpSenderOptions options) : options_(std::move(options)) {}

ViconUdpSender::~ViconUdpSender() {
  stop();
}

std::optional<std::string> ViconUdpSender::start(FrameProvider provider) {
  return start_emulator(worker_, options_.rate_hz,
                        std::make_unique<Impl>(options_, counters_, std::move(provider)), port_);
}

void ViconUdpSender::publish(core::MocapFrame frame) {
  if (auto* impl = worker_.get()) impl->publish(std::move(frame));
}

void ViconUdpSender::stop() {
  worker_.stop();
}

std::string ViconUdpSender::summary() const {
  const auto& c = counters_;
  return std::to_string(c.frames.load()) + " frames, " + std::to_string(c.datagrams.load()) +
         " datagrams, " + std::to_string(c.send_errors.load()) + " send errors";
}

}  // namespace mocaplink::sources
