#include "mocaplink/sources/vicon_server.hpp"

#include <array>
#include <chrono>
#include <deque>
#include <mutex>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <asio.hpp>

#include "mocaplink/sources/emulator_support.hpp"
#include "mocaplink/wire/vicon_packet.hpp"
#include "mocaplink/wire/vicon_server_session.hpp"

namespace mocaplink::sources {

namespace vw = wire::vicon;
using asio::ip::tcp;
using SteadyClock = std::chrono::steady_clock;

namespace {

// Client packets are requests of a few bytes (a Filter with many subjects at most): 1 MiB is
// generous and keeps a hostile client from making us allocate more.
constexpr std::uint32_t kMaxClientBodyBytes = 1024u * 1024u;
// Replies (ping echoes, pulled frames) a client may leave unread before we give up on it.
constexpr std::size_t kMaxQueuedReplies = 64;
constexpr auto kKeepAliveAfter = std::chrono::seconds(1);

std::vector<std::byte> keep_alive_packet() {
  vw::PacketBuilder b;
  b.add(vw::KeepAlive{});
  return b.finish();
}

}  // namespace

class ViconServer::Impl {
 public:
  Impl(const ViconServerOptions& options, ViconServerCounters& counters)
      : options_(options), counters_(counters) {}

  std::optional<std::string> listen() {
    return listen_tcp(acceptor_, options_.listen_host, options_.port);
  }

  std::uint16_t bound_port() const { return acceptor_.local_endpoint().port(); }

  void run(FrameProvider provider) {
    provider_ = std::move(provider);
    accept();
    keep_alive_tick();
    if (provider_) {
      schedule_.emplace(options_.rate_hz, SteadyClock::now());
      schedule_tick();
    }
    io_.run();
    asio::error_code ignored;
    acceptor_.close(ignored);
    for (const auto& c : connections_) c->socket.close(ignored);
    connections_.clear();
  }

  void stop() { io_.stop(); }

  void publish(core::MocapFrame frame) {
    asio::post(io_, [this, f = std::move(frame)] { produce(f); });
  }

 private:
  struct Connection {
    explicit Connection(tcp::socket s) : socket(std::move(s)) {}
    tcp::socket socket;
    vw::ServerSession session;
    std::array<std::byte, vw::kPacketHeaderBytes> header{};
    std::vector<std::byte> body;
    std::deque<std::vector<std::byte>> queue;  // front is being written when `writing`
    std::size_t queued_frames = 0;             // frame packets in `queue` (from on_new_frame)
    std::deque<bool> queued_is_frame;
    bool writing = false;
    bool closed = false;
    SteadyClock::time_point last_enqueue = SteadyClock::now();
  };
  using ConnectionPtr = std::shared_ptr<Connection>;

  void schedule_tick() {
    tick_timer_.expires_at(schedule_->due());
    tick_timer_.async_wait([this](const asio::error_code& ec) {
      if (ec) return;
      if (auto frame = provider_(schedule_->tick())) produce(*frame);
      schedule_->advance(SteadyClock::now());
      schedule_tick();
    });
  }

  void produce(const core::MocapFrame& frame) {
    const double rate =
        frame.frame_rate_hz && *frame.frame_rate_hz > 0.0 ? *frame.frame_rate_hz : options_.rate_hz;
    latest_ = std::make_shared<const vw::ServedFrame>(
        builder_.build(frame, vw::frame_period_ticks(rate)));
    ++counters_.frames;
    for (const auto& c : connections_) {
      if (c->queued_frames >= options_.queue_frames) {
        // Full: skip this frame for this client before encoding it, so that the session's record
        // of what the client holds (the "unchanged" cache) stays true (§7, §6.2).
        if (c->session.streaming() || c->session.pending_next() > 0) ++counters_.frames_dropped;
        continue;
      }
      if (auto packet = c->session.on_new_frame(*latest_)) enqueue(c, std::move(*packet), true);
    }
  }

  void accept() {
    acceptor_.async_accept([this](const asio::error_code& ec, tcp::socket socket) {
      if (ec) {
        if (ec != asio::error::operation_aborted) accept();
        return;
      }
      if (connections_.size() >= options_.max_clients) {
        ++counters_.clients_rejected;
        asio::error_code ignored;
        socket.close(ignored);
      } else {
        asio::error_code ignored;
        socket.set_option(tcp::no_delay(true), ignored);
        auto c = std::make_shared<Connection>(std::move(socket));
        connections_.insert(c);
        ++counters_.clients_accepted;
        counters_.clients_now = connections_.size();
        enqueue(c, c->session.greeting(), false);  // the server speaks first (§6.1)
        read_header(c);
      }
      accept();
    });
  }

  void close(const ConnectionPtr& c) {
    if (c->closed) return;
    c->closed = true;
    asio::error_code ignored;
    c->socket.shutdown(tcp::socket::shutdown_both, ignored);
    c->socket.close(ignored);
    connections_.erase(c);
    counters_.clients_now = connections_.size();
  }

  void read_header(const ConnectionPtr& c) {
    asio::async_read(c->socket, asio::buffer(c->header),
                     [this, c](const asio::error_code& ec, std::size_t) {
                       if (ec || c->closed) return close(c);
                       auto length = vw::parse_packet_header(c->header, kMaxClientBodyBytes);
                       if (!length) {
                         ++counters_.malformed_requests;
                         return close(c);
                       }
                       c->body.resize(length.value());
                       read_body(c);
                     });
  }

  void read_body(const ConnectionPtr& c) {
    asio::async_read(c->socket, asio::buffer(c->body),
                     [this, c](const asio::error_code& ec, std::size_t) {
                       if (ec || c->closed) return close(c);
                       auto replies = c->session.on_client_packet(c->body, latest_.get());
                       if (!replies) {
                         ++counters_.malformed_requests;
                         return close(c);
                       }
                       for (auto& p : replies.value()) enqueue(c, std::move(p), false);
                       if (!c->closed) read_header(c);
                     });
  }

  void enqueue(const ConnectionPtr& c, std::vector<std::byte> packet, bool is_frame) {
    if (c->closed) return;
    if (c->queue.size() >= options_.queue_frames + kMaxQueuedReplies) return close(c);
    c->queue.push_back(std::move(packet));
    c->queued_is_frame.push_back(is_frame);
    if (is_frame) ++c->queued_frames;
    c->last_enqueue = SteadyClock::now();
    if (!c->writing) write_next(c);
  }

  void write_next(const ConnectionPtr& c) {
    if (c->queue.empty() || c->closed) {
      c->writing = false;
      return;
    }
    c->writing = true;
    asio::async_write(c->socket, asio::buffer(c->queue.front()),
                      [this, c](const asio::error_code& ec, std::size_t) {
                        if (ec || c->closed) return close(c);
                        ++counters_.packets_sent;
                        if (c->queued_is_frame.front()) --c->queued_frames;
                        c->queue.pop_front();
                        c->queued_is_frame.pop_front();
                        write_next(c);
                      });
  }

  void keep_alive_tick() {
    keep_alive_timer_.expires_after(kKeepAliveAfter);
    keep_alive_timer_.async_wait([this](const asio::error_code& ec) {
      if (ec) return;
      const auto now = SteadyClock::now();
      const std::vector<ConnectionPtr> all(connections_.begin(), connections_.end());
      for (const auto& c : all) {
        if (now - c->last_enqueue >= kKeepAliveAfter) enqueue(c, keep_alive_packet(), false);
      }
      keep_alive_tick();
    });
  }

  const ViconServerOptions& options_;
  ViconServerCounters& counters_;
  asio::io_context io_;  // first: destroyed after the sockets and timers that use it
  tcp::acceptor acceptor_{io_};
  asio::steady_timer tick_timer_{io_};
  asio::steady_timer keep_alive_timer_{io_};
  std::set<ConnectionPtr> connections_;
  FrameProvider provider_;
  std::optional<TickSchedule> schedule_;
  vw::ServedFrameBuilder builder_;
  std::shared_ptr<const vw::ServedFrame> latest_;
};

ViconServer::ViconServer(ViconServerOptions options) : options_(std::move(options)) {}

ViconServer::~ViconServer() {
  stop();
}

std::optional<std::string> ViconServer::start(FrameProvider provider) {
  return start_emulator(impl_, port_, options_.rate_hz, std::move(provider), options_, counters_);
}

void ViconServer::publish(core::MocapFrame frame) {
  if (auto* impl = impl_.get()) impl->publish(std::move(frame));
}

void ViconServer::stop() {
  impl_.stop();
}

std::string ViconServer::summary() const {
  const auto& c = counters_;
  return std::to_string(c.frames.load()) + " frames, " + std::to_string(c.clients_accepted.load()) +
         " clients, " + std::to_string(c.frames_dropped.load()) +
         " frames dropped for slow clients, " + std::to_string(c.malformed_requests.load()) +
         " malformed requests";
}

}  // namespace mocaplink::sources
