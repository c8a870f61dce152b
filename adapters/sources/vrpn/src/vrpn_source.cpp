#include "mocaplink/sources/vrpn_source.hpp"

#include <algorithm>
#include <array>
#include <optional>
#include <utility>

#include <asio.hpp>

#include "mocaplink/io/clock.hpp"
#include "mocaplink/wire/vrpn_client.hpp"

namespace mocaplink::sources {

namespace vr = wire::vrpn;
using asio::ip::tcp;

namespace {

// One read takes what the socket has, up to this; a message never exceeds header + kMaxPayload.
constexpr std::size_t kReadChunk = 64 * 1024;

std::string join(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace

class VrpnSource::Session {
 public:
  Session(VrpnSource& owner, FrameSink on_frame, StateSink on_state)
      : owner_(owner), on_frame_(std::move(on_frame)), on_state_(std::move(on_state)) {}

  void run() {
    open();  // nothing runs before io_.run() below: the handlers only queue
    io_.run();
    drop_socket();
  }

  void stop() { io_.stop(); }

 private:
  // Every attempt gets a fresh Link; a handler whose Link is no longer current does nothing.
  struct Link {
    explicit Link(asio::io_context& io) : socket(io) {}
    tcp::socket socket;
    std::array<std::byte, vr::kCookieBytes> cookie{};
    std::vector<std::byte> chunk = std::vector<std::byte>(kReadChunk);
    std::vector<std::byte> pending;  // bytes of messages not yet complete
    vr::ClientTables tables;
    bool accepted = false;  // the server's cookie was good
  };
  using LinkPtr = std::shared_ptr<Link>;

  static vr::AssemblerConfig assembler_config(const VrpnOptions& o) {
    vr::AssemblerConfig c;
    c.lost_after = o.lost;
    c.frozen_after = o.frozen;
    return c;
  }

  bool current(const LinkPtr& link) const { return link == link_; }

  void report_state(SourceState s, const std::string& detail) {
    if (on_state_) on_state_(s, detail);
  }

  void open() {
    if (opened_++ > 0) ++owner_.counters_.reconnects;
    auto link = std::make_shared<Link>(io_);
    link_ = link;
    const std::string where = opts_.target.host + ":" + std::to_string(opts_.target.port);
    report_state(SourceState::connecting, where);
    deadline_.expires_after(opts_.connect_timeout);
    deadline_.async_wait([this, link](const asio::error_code& ec) {
      if (!ec && current(link) && !link->accepted) drop(link, "connect timeout", false);
    });
    resolver_.async_resolve(
        opts_.target.host, std::to_string(opts_.target.port),
        [this, link, where](const asio::error_code& ec, const tcp::resolver::results_type& to) {
          if (!current(link)) return;
          if (ec) return drop(link, "resolve " + where + ": " + ec.message(), false);
          asio::async_connect(link->socket, to,
                              [this, link](const asio::error_code& cec, const tcp::endpoint&) {
                                if (current(link)) on_connected(link, cec);
                              });
        });
  }

  void on_connected(const LinkPtr& link, const asio::error_code& ec) {
    if (ec) return drop(link, "connect: " + ec.message(), false);
    asio::error_code ignored;
    link->socket.set_option(tcp::no_delay(true), ignored);
    // §2: both sides send their cookie at once; the server says nothing more before it has ours.
    auto ours = std::make_shared<std::array<std::byte, vr::kCookieBytes>>(vr::make_cookie('0'));
    asio::async_write(link->socket, asio::buffer(*ours),
                      [this, link, ours](const asio::error_code& wec, std::size_t) {
                        if (current(link) && wec) drop(link, "write: " + wec.message(), false);
                      });
    asio::async_read(link->socket, asio::buffer(link->cookie),
                     [this, link](const asio::error_code& rec, std::size_t n) {
                       if (current(link)) on_cookie(link, rec, n);
                     });
  }

  void on_cookie(const LinkPtr& link, const asio::error_code& ec, std::size_t n) {
    if (ec) return drop(link, "read: " + ec.message(), n > 0);
    auto cookie = vr::parse_cookie(link->cookie);
    if (!cookie) return drop(link, "bad cookie: " + cookie.error().reason, true);
    link->accepted = true;
    deadline_.cancel();
    backoff_.reset();
    ++owner_.vrpn_counters_.connections;
    {
      const std::lock_guard lock(owner_.mutex_);
      owner_.trackers_.clear();
    }
    report_state(SourceState::connected, "server " + cookie.value().magic);
    watch_silence(link);
    read_more(link);
  }

  void watch_silence(const LinkPtr& link) {
    silence_.expires_after(opts_.target.timeout);
    silence_.async_wait([this, link](const asio::error_code& ec) {
      if (ec || !current(link)) return;
      ++owner_.vrpn_counters_.timeouts;
      drop(link,
           "no data from the server for " + std::to_string(opts_.target.timeout.count()) + " ms",
           false);
    });
  }

  void read_more(const LinkPtr& link) {
    link->socket.async_read_some(
        asio::buffer(link->chunk), [this, link](const asio::error_code& ec, std::size_t n) {
          if (!current(link)) return;
          if (ec) {
            return drop(link, "read: " + ec.message(), !link->pending.empty());
          }
          owner_.vrpn_counters_.bytes += n;
          watch_silence(link);
          if (consume(link, n)) read_more(link);
        });
  }

  // Appends `n` fresh bytes and handles every complete message; false if the link was dropped.
  bool consume(const LinkPtr& link, std::size_t n) {
    auto& buf = link->pending;
    buf.insert(buf.end(), link->chunk.begin(),
               link->chunk.begin() + static_cast<std::ptrdiff_t>(n));
    std::size_t at = 0;
    while (buf.size() - at >= vr::kHeaderBytes) {
      const std::span<const std::byte> rest(buf.data() + at, buf.size() - at);
      auto header = vr::parse_header(rest.first(vr::kHeaderBytes));
      if (!header) {
        drop(link, "malformed message header: " + header.error().reason, true);
        return false;
      }
      const std::size_t whole = vr::kHeaderBytes + header.value().padded_payload_bytes();
      if (rest.size() < whole) break;
      const auto payload = rest.subspan(vr::kHeaderBytes, header.value().payload_bytes());
      at += whole;
      if (!on_message(link, header.value(), payload)) return false;
    }
    buf.erase(buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(at));
    if (senders_changed_) {  // once per read: a description burst is one line
      senders_changed_ = false;
      report_state(SourceState::connected, "senders: " + join(owner_.trackers()));
    }
    asio::error_code ignored;
    if (link->socket.available(ignored) == 0) {
      deliver(assembler_.on_drained());
      watch_idle();  // an incomplete round settles (FrameAssembler::on_drained)
    }
    return true;
  }

  bool on_message(const LinkPtr& link, const vr::Header& header,
                  std::span<const std::byte> payload) {
    ++owner_.vrpn_counters_.messages;
    auto outcome = link->tables.apply(header, payload);
    if (!outcome) {
      drop(
          link,
          "malformed message (type " + std::to_string(header.type) + "): " + outcome.error().reason,
          true);
      return false;
    }
    vr::MessageOutcome& out = outcome.value();
    if (out.unknown_id) ++owner_.vrpn_counters_.unknown_ids;
    if (!out.new_sender.empty()) {
      const std::lock_guard lock(owner_.mutex_);
      owner_.trackers_.push_back(out.new_sender);
      senders_changed_ = true;
    }
    if (!out.report) return true;
    if (!wanted(out.report->tracker)) {
      ++owner_.vrpn_counters_.other_trackers;
      return true;
    }
    ++owner_.vrpn_counters_.reports;
    const auto frozen_before = assembler_.frozen_samples();
    deliver(assembler_.on_report(*out.report, io::host_now()));
    owner_.vrpn_counters_.frozen += assembler_.frozen_samples() - frozen_before;
    watch_idle();
    return true;
  }

  bool wanted(const std::string& tracker) const {
    const auto& list = opts_.target.trackers;
    return list.empty() || std::find(list.begin(), list.end(), tracker) != list.end();
  }

  // Asks the assembler again when a silence would make its bodies lost.
  void watch_idle() {
    const auto when = assembler_.idle_deadline();
    if (!when) return;
    using Steady = std::chrono::steady_clock;
    idle_.expires_at(
        Steady::time_point(std::chrono::duration_cast<Steady::duration>(when->time_since_epoch())));
    idle_.async_wait([this](const asio::error_code& ec) {
      if (ec) return;
      deliver(assembler_.on_idle(io::host_now()));
      watch_idle();
    });
  }

  // `received` is when the frame's data arrived, not when its round was closed: a round closed
  // late is judged by its age downstream (the daemon skips and counts one too old to send).
  void deliver(std::optional<vr::AssembledFrame> assembled) {
    if (!assembled) return;
    ++owner_.counters_.frames;
    if (on_frame_) on_frame_(std::move(assembled->frame), assembled->received);
  }

  // Ends `link` and schedules the next attempt. `malformed`: the server's bytes were at fault.
  void drop(const LinkPtr& link, const std::string& reason, bool malformed) {
    if (!current(link)) return;
    if (malformed) ++owner_.counters_.malformed;
    {
      const std::lock_guard lock(owner_.mutex_);
      owner_.last_error_ = reason;
    }
    link_.reset();
    drop_socket(link);
    deadline_.cancel();
    silence_.cancel();
    idle_.cancel();
    assembler_.reset();  // the round and the poses of this connection never reach a frame
    report_state(SourceState::disconnected, reason);
    retry_.expires_after(backoff_.next());
    retry_.async_wait([this](const asio::error_code& ec) {
      if (!ec) open();
    });
  }

  void drop_socket(const LinkPtr& link = nullptr) {
    const LinkPtr l = link ? link : link_;
    resolver_.cancel();
    if (!l) return;
    asio::error_code ignored;
    l->socket.shutdown(tcp::socket::shutdown_both, ignored);
    l->socket.close(ignored);
  }

  VrpnSource& owner_;
  const VrpnSourceOptions& opts_ = owner_.options_;
  asio::io_context io_;  // before the sockets and timers that use it, destroyed after them
  FrameSink on_frame_;
  StateSink on_state_;
  vr::FrameAssembler assembler_{assembler_config(opts_.target)};
  tcp::resolver resolver_{io_};
  LinkPtr link_;
  asio::steady_timer deadline_{io_}, silence_{io_}, idle_{io_}, retry_{io_};
  core::RetrySchedule backoff_{opts_.retry};
  std::uint64_t opened_ = 0;
  bool senders_changed_ = false;
};

VrpnSource::VrpnSource(VrpnSourceOptions options, std::string url)
    : options_(std::move(options)), url_(std::move(url)) {}

VrpnSource::~VrpnSource() {
  stop();
}

void VrpnSource::start(FrameSink on_frame, StateSink on_state) {
  if (!worker_.running()) {
    worker_.start(std::make_unique<Session>(*this, std::move(on_frame), std::move(on_state)));
  }
}

void VrpnSource::stop() {
  worker_.stop();
}

std::string VrpnSource::last_error() const {
  const std::lock_guard lock(mutex_);
  return last_error_;
}

std::vector<std::string> VrpnSource::trackers() const {
  const std::lock_guard lock(mutex_);
  return trackers_;
}

}  // namespace mocaplink::sources
