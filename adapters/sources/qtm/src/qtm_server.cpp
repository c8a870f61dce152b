#include "mocaplink/sources/qtm_server.hpp"

#include <array>
#include <chrono>
#include <deque>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <asio.hpp>

#include "mocaplink/wire/qtm_frame.hpp"

namespace mocaplink::sources {

namespace wq = wire::qtm;
using asio::ip::tcp;
using asio::ip::udp;

namespace {

// Client commands are short; a SetParameters XML is the largest a client may send us.
constexpr std::uint32_t kMaxClientPacketBytes = 1024u * 1024u;
constexpr std::size_t kMaxQueuedReplies = 64;

}  // namespace

class QtmServer::Impl {
 public:
  Impl(const QtmServerOptions& options, QtmServerCounters& counters)
      : options_(options), counters_(counters) {}

  std::optional<std::string> listen() {
    asio::error_code ec;
    const auto address = asio::ip::make_address(options_.listen_host, ec);
    if (ec) return "bad listen address '" + options_.listen_host + "': " + ec.message();
    const tcp::endpoint at(address, options_.port);
    const std::string where = options_.listen_host + ":" + std::to_string(options_.port);
    acceptor_.open(at.protocol(), ec);
    if (!ec) acceptor_.set_option(tcp::acceptor::reuse_address(true), ec);
    if (!ec) acceptor_.bind(at, ec);
    if (!ec) acceptor_.listen(asio::socket_base::max_listen_connections, ec);
    if (!ec) udp_.open(at.address().is_v6() ? udp::v6() : udp::v4(), ec);
    if (ec) return "cannot listen on " + where + ": " + ec.message();
    return std::nullopt;
  }

  std::uint16_t bound_port() const { return acceptor_.local_endpoint().port(); }

  void run(FrameProvider provider) {
    provider_ = std::move(provider);
    if (provider_) {
      started_ = std::chrono::steady_clock::now();
      tick();
    }
    // Until the first frame nothing may be pending (no accept yet): run until stop().
    const auto idle = asio::make_work_guard(io_);
    io_.run();
    asio::error_code ignored;
    acceptor_.close(ignored);
    udp_.close(ignored);
    for (const auto& c : clients_) c->socket.close(ignored);
    clients_.clear();
  }

  void stop() { io_.stop(); }

  void publish(core::MocapFrame frame) {
    asio::post(io_, [this, f = std::move(frame)] { serve(f); });
  }

 private:
  struct Client {
    Client(tcp::socket s, const wq::ServerSettings& settings)
        : socket(std::move(s)), session(settings) {}
    tcp::socket socket;
    wq::ServerSession session;
    std::array<std::byte, wq::kHeaderBytes> header{};
    std::vector<std::byte> payload;
    std::deque<std::pair<std::vector<std::byte>, bool>> out;  // packet, is a frame
    std::size_t frames_queued = 0;
    bool writing = false;
    bool closed = false;
    bool closing = false;  // rejected: closed once its error packet is written
    std::optional<udp::endpoint> udp_to;
  };
  using ClientPtr = std::shared_ptr<Client>;

  std::chrono::steady_clock::duration period() const {
    return std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(1.0 / options_.rate_hz));
  }

  // The provider's drift-free schedule; after a stall it resumes from now instead of bursting.
  void tick() {
    const auto due = started_ + period() * static_cast<std::int64_t>(ticks_);
    tick_timer_.expires_at(due);
    tick_timer_.async_wait([this](const asio::error_code& ec) {
      if (ec) return;
      if (auto frame = provider_(ticks_)) serve(*frame);
      ++ticks_;
      if (std::chrono::steady_clock::now() - started_ >
          period() * static_cast<std::int64_t>(ticks_ + 5)) {
        started_ = std::chrono::steady_clock::now() - period() * static_cast<std::int64_t>(ticks_);
      }
      tick();
    });
  }

  void serve(const core::MocapFrame& frame) {
    auto served = std::make_shared<wq::ServedFrame>(wq::served_frame(frame));
    ++counters_.frames;
    const bool changed = latest_ && latest_->names != served->names;
    // Clients are welcomed from the first frame on: before it there is no body list to answer
    // GetParameters with, and the official client reads that list once, at connect.
    if (!latest_) accept();
    latest_ = served;
    const std::vector<ClientPtr> all(clients_.begin(), clients_.end());
    if (changed) {
      ++counters_.body_list_changes;
      for (const auto& c : all) {
        push(c, wq::encode_event(static_cast<std::uint8_t>(wq::Event::camera_settings_changed)),
             false);
      }
    }
    for (const auto& c : all) {
      if (c->closed || c->closing || !c->session.streaming()) continue;
      if (!c->udp_to && c->frames_queued >= options_.queue_frames) {
        ++counters_.frames_dropped;
        continue;
      }
      auto packet = c->session.on_new_frame(*latest_);
      if (!packet) continue;
      if (c->udp_to) {
        asio::error_code ignored;
        udp_.send_to(asio::buffer(*packet), *c->udp_to, 0, ignored);
        ++counters_.packets_sent;
      } else {
        push(c, std::move(*packet), true);
      }
    }
  }

  void accept() {
    acceptor_.async_accept([this](const asio::error_code& ec, tcp::socket socket) {
      if (ec == asio::error::operation_aborted) return;
      if (!ec) welcome(std::move(socket));
      accept();
    });
  }

  void welcome(tcp::socket socket) {
    asio::error_code ignored;
    socket.set_option(tcp::no_delay(true), ignored);
    auto c = std::make_shared<Client>(std::move(socket), options_.session);
    clients_.insert(c);
    if (clients_.size() > options_.max_clients) {
      ++counters_.clients_rejected;
      push(c, wq::encode_text(wq::PacketType::error, wq::kMaxClientsError), false);
      c->closing = true;
      return;
    }
    ++counters_.clients_accepted;
    counters_.clients_now = clients_.size();
    push(c, wq::ServerSession::welcome(), false);
    read_header(c);
  }

  void close(const ClientPtr& c) {
    asio::error_code ignored;
    c->closed = true;
    c->socket.shutdown(tcp::socket::shutdown_both, ignored);
    c->socket.close(ignored);
    clients_.erase(c);
    counters_.clients_now = clients_.size();
  }

  void read_header(const ClientPtr& c) {
    asio::async_read(c->socket, asio::buffer(c->header),
                     [this, c](const asio::error_code& ec, std::size_t) {
                       if (ec || c->closed) return close(c);
                       auto header = wq::parse_header(c->header, kMaxClientPacketBytes);
                       if (!header) {
                         ++counters_.malformed_requests;
                         return close(c);
                       }
                       c->payload.resize(header.value().size - wq::kHeaderBytes);
                       read_payload(c, header.value().type);
                     });
  }

  void read_payload(const ClientPtr& c, std::uint32_t type) {
    asio::async_read(c->socket, asio::buffer(c->payload),
                     [this, c, type](const asio::error_code& ec, std::size_t) {
                       if (ec || c->closed) return close(c);
                       static const std::vector<std::string> no_names;
                       const auto before = c->session.errors_sent();
                       auto replies = c->session.on_client_packet(
                           type, c->payload, latest_ ? latest_->names : no_names, latest_.get());
                       counters_.errors_sent += c->session.errors_sent() - before;
                       update_udp(c);
                       for (auto& p : replies) push(c, std::move(p), false);
                       if (!c->closed) read_header(c);
                     });
  }

  void update_udp(const ClientPtr& c) {
    const auto& target = c->session.udp();
    if (!c->session.streaming() || !target) {
      c->udp_to.reset();
      return;
    }
    asio::error_code ec;
    asio::ip::address address = c->socket.remote_endpoint(ec).address();
    if (!target->address.empty()) address = asio::ip::make_address(target->address, ec);
    if (ec) {
      c->udp_to.reset();
      push(c, wq::encode_text(wq::PacketType::error, "Bad UDP address " + target->address), false);
      return;
    }
    c->udp_to = udp::endpoint(address, target->port);
  }

  void push(const ClientPtr& c, std::vector<std::byte> packet, bool frame) {
    if (c->closed || c->closing) return;
    if (c->out.size() >= options_.queue_frames + kMaxQueuedReplies) return close(c);
    c->out.emplace_back(std::move(packet), frame);
    if (frame) ++c->frames_queued;
    if (!c->writing) write(c);
  }

  void write(const ClientPtr& c) {
    c->writing = !c->out.empty();
    if (!c->writing) {
      if (c->closing) close(c);  // a rejected client, its error written
      return;
    }
    asio::async_write(c->socket, asio::buffer(c->out.front().first),
                      [this, c](const asio::error_code& ec, std::size_t) {
                        if (ec || c->closed) return close(c);
                        ++counters_.packets_sent;
                        if (c->out.front().second) --c->frames_queued;
                        c->out.pop_front();
                        write(c);
                      });
  }

  const QtmServerOptions& options_;
  QtmServerCounters& counters_;
  asio::io_context io_;  // first: destroyed after the sockets and timers that use it
  tcp::acceptor acceptor_{io_};
  udp::socket udp_{io_};
  asio::steady_timer tick_timer_{io_};
  std::set<ClientPtr> clients_;
  FrameProvider provider_;
  std::chrono::steady_clock::time_point started_{};
  std::uint64_t ticks_ = 0;
  std::shared_ptr<const wq::ServedFrame> latest_;
};

QtmServer::QtmServer(QtmServerOptions options) : options_(std::move(options)) {
  options_.session.frequency_hz = options_.rate_hz;
}

QtmServer::~QtmServer() {
  stop();
}

std::optional<std::string> QtmServer::start(FrameProvider provider) {
  return start_emulator(impl_, port_, options_.rate_hz, std::move(provider), options_, counters_);
}

void QtmServer::publish(core::MocapFrame frame) {
  if (auto* impl = impl_.get()) impl->publish(std::move(frame));
}

void QtmServer::stop() {
  impl_.stop();
}

std::string QtmServer::summary() const {
  const auto& c = counters_;
  return std::to_string(c.frames.load()) + " frames, " + std::to_string(c.clients_accepted.load()) +
         " clients, " + std::to_string(c.body_list_changes.load()) + " body list changes, " +
         std::to_string(c.frames_dropped.load()) + " frames dropped for slow clients, " +
         std::to_string(c.errors_sent.load()) + " errors sent";
}

}  // namespace mocaplink::sources
