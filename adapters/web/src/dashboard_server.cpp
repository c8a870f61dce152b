#include "mocaplink/web/dashboard_server.hpp"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>

#include <httplib.h>
#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "mocaplink/web/alerts.hpp"
#include "mocaplink/web/assets.hpp"
#include "mocaplink/web/connection_limits.hpp"
#include "mocaplink/web/http_auth.hpp"
#include "mocaplink/web/status_json.hpp"
#include "request_stream.hpp"
#include "socket_io.hpp"

namespace mocaplink::web {
// Named, not anonymous: DashboardServer::Impl holds a LimitedServer (GCC warns when a class
// holds a member of an anonymous-namespace type outside the main file, as in a unity build).
namespace dashboard_detail {

using Clock = std::chrono::steady_clock;
using nlohmann::json;

constexpr std::size_t kMaxBodyBytes = 64 * 1024;  // a vehicle spec is well under 1 KiB
constexpr std::string_view kVehiclePath = "/api/vehicles/";

// Browsers get the page and talk only to this origin; nothing is loaded from elsewhere.
constexpr const char* kContentSecurityPolicy =
    "default-src 'self'; img-src 'self' data:; style-src 'self'; script-src 'self'; "
    "connect-src 'self'; frame-ancestors 'none'; base-uri 'none'; form-action 'none'";

void send_json(httplib::Response& res, int status, const json& body) {
  res.status = status;
  res.set_header("Cache-Control", "no-store");
  res.set_content(body.dump(), "application/json");
}

void send_error(httplib::Response& res, const ApiError& error) {
  send_json(res, error.status, json{{"error", error.error}, {"field", error.field}});
}

void send_method_not_allowed(httplib::Response& res, const char* allow) {
  res.set_header("Allow", allow);
  send_error(res, ApiError{405, std::string("method not allowed; allowed: ") + allow, ""});
}

bool is_json_content_type(const std::string& content_type) {
  const std::string_view type = std::string_view(content_type).substr(0, content_type.find(';'));
  return type == "application/json";
}

/// 1, 10, 100...: when a counted refusal is logged (a summary, not a line per refusal).
bool is_power_of_ten(std::uint64_t n) {
  while (n >= 10 && n % 10 == 0) n /= 10;
  return n == 1;
}

std::string host_for_url(const std::string& host) {
  return host.find(':') != std::string::npos ? "[" + host + "]" : host;
}

/// httplib's task queue with one thread per connection (up to `max_threads`; beyond that,
/// connections wait in FIFO order for a thread): an idle connection, a client sending one byte a
/// second or an event stream holds only its own thread, never one that another request needs
/// (httplib's fixed pool let 16 idle connections stall /api/status for seconds). Idle threads
/// cost no CPU; a thread ends with its connection (LimitedServer's timeouts).
class ConnectionThreads final : public httplib::TaskQueue {
 public:
  explicit ConnectionThreads(std::size_t max_threads) : max_threads_(max_threads) {}
  ~ConnectionThreads() override { shutdown(); }
  ConnectionThreads(const ConnectionThreads&) = delete;
  ConnectionThreads& operator=(const ConnectionThreads&) = delete;

  void enqueue(std::function<void()> fn) override {
    std::lock_guard lock(mutex_);
    if (threads_ >= max_threads_) {
      waiting_.push_back(std::move(fn));
      return;
    }
    ++threads_;
    std::thread([this, job = std::move(fn)]() mutable { run(std::move(job)); }).detach();
  }

  /// Waits for every connection to end (the listener has stopped; event streams end at once).
  void shutdown() override {
    std::unique_lock lock(mutex_);
    idle_.wait(lock, [this] { return threads_ == 0; });
  }

 private:
  void run(std::function<void()> job) {
    while (true) {
      job();
      std::lock_guard lock(mutex_);
      if (waiting_.empty()) {
        --threads_;
        idle_.notify_all();  // under the lock: the queue may be destroyed once threads_ is 0
        return;
      }
      job = std::move(waiting_.front());
      waiting_.pop_front();
    }
  }

  const std::size_t max_threads_;
  std::mutex mutex_;
  std::condition_variable idle_;
  std::size_t threads_ = 0;
  std::deque<std::function<void()>> waiting_;
};

/// httplib's server with its connection loop replaced (httplib lets a subclass serve a socket:
/// SSLServer does the same): a connection from an address that already holds
/// `max_connections_per_client` is closed before anything is read, and every request is read
/// through a RequestStream, so it must arrive within `request_timeout` of its first byte.
/// Between requests a connection may stay silent for `idle_timeout`.
class LimitedServer final : public httplib::Server {
 public:
  explicit LimitedServer(const DashboardServerConfig& config)
      // 0 is refused by start(); until then ClientSlots must still be valid.
      : slots_(std::max<std::size_t>(config.max_connections_per_client, 1)),
        request_timeout_(config.request_timeout),
        idle_timeout_(config.idle_timeout) {}

  [[nodiscard]] ConnectionsView counters() const {
    return ConnectionsView{slots_.open(), slots_.refused(), timed_out_.load()};
  }

 private:
  bool process_and_close_socket(socket_t sock) override {
    const std::string address = detail::socket_address(sock, false);
    if (!slots_.try_acquire(address)) {
      detail::close_connection(sock);
      const std::uint64_t refused = slots_.refused();
      if (is_power_of_ten(refused)) {  // a summary, not a line per refusal (a scanner loops)
        spdlog::warn(
            "dashboard: {} connection(s) refused so far: the client address already held {} "
            "(latest from {})",
            refused, slots_.per_client(), address);
      }
      return false;
    }
    const bool served = serve(sock);
    slots_.release(address);
    detail::close_connection(sock);
    return served;
  }

  /// Requests one after the other on one connection (keep-alive), as httplib's own loop does.
  bool serve(socket_t sock) {
    bool ok = false;
    for (std::size_t left = keep_alive_max_count_; left > 0 && svr_sock_ != INVALID_SOCKET;) {
      --left;
      if (detail::wait_socket(sock, false, idle_timeout_) != detail::SocketWait::ready) break;
      RequestDeadline deadline(request_timeout_, idle_timeout_);
      deadline.start(RequestDeadline::Clock::now());
      detail::RequestStream stream(sock, deadline, write_timeout());
      bool closed = false;
      ok = process_request(stream, left == 0, closed, nullptr);
      if (stream.timed_out()) {
        ++timed_out_;
        stream.answer_timed_out();
        return false;
      }
      if (!ok || closed) break;
    }
    return ok;
  }

  [[nodiscard]] std::chrono::milliseconds write_timeout() const {
    return std::chrono::seconds(write_timeout_sec_) +
           std::chrono::duration_cast<std::chrono::milliseconds>(
               std::chrono::microseconds(write_timeout_usec_));
  }

  ClientSlots slots_;
  const std::chrono::milliseconds request_timeout_;
  const std::chrono::milliseconds idle_timeout_;
  std::atomic<std::uint64_t> timed_out_{0};
};

}  // namespace dashboard_detail

using namespace dashboard_detail;  // NOLINT(google-build-using-namespace): this file's own helpers

class DashboardServer::Impl {
 public:
  Impl(DashboardBackend& backend, DashboardServerConfig config)
      : backend_(backend), config_(std::move(config)), server_(config_) {}

  ~Impl() { stop(); }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  std::optional<std::string> start();
  void stop();
  [[nodiscard]] std::uint16_t port() const { return port_; }

 private:
  struct Snapshot {
    json status;
    std::string text;
  };

  void install_routes();
  httplib::Server::HandlerResponse check_access(const httplib::Request& req,
                                                httplib::Response& res);
  /// True when the request's Host names this server, or need not (see
  /// DashboardServerConfig::allowed_hosts); otherwise answers 403 and counts it.
  bool check_host(const httplib::Request& req, httplib::Response& res);
  std::shared_ptr<const Snapshot> snapshot();
  void invalidate_snapshot();
  /// The vehicle as in the status. After a change that succeeded (`changed`), a status that does
  /// not list it yet (the daemon answered with its previous picture) gives {"name": NAME} with
  /// the success status, never a 404 that would deny the change.
  void respond_vehicle(httplib::Response& res, int status, const std::string& name,
                       bool changed = false);
  void apply_and_respond(httplib::Response& res, const VehicleChange& change,
                         const std::string& name, int success_status);
  void serve_events(httplib::Response& res);

  DashboardBackend& backend_;
  DashboardServerConfig config_;
  LimitedServer server_;
  std::thread thread_;
  std::uint16_t port_ = 0;
  bool started_ = false;

  std::mutex snapshot_mutex_;  // guards the three below; serialises backend_.status()
  std::shared_ptr<const Snapshot> snapshot_;
  Clock::time_point snapshot_time_{};
  AlertMonitor alerts_;
  const Clock::time_point created_ = Clock::now();

  std::atomic<bool> stopping_{false};
  std::mutex stop_mutex_;
  std::condition_variable stop_cv_;
  std::atomic<std::size_t> event_clients_{0};
  std::atomic<std::uint64_t> host_refused_{0};
};

std::optional<std::string> DashboardServer::Impl::start() {
  const std::string address = host_for_url(config_.host) + ":" + std::to_string(config_.port);
  if (started_) return "the dashboard server is already started";
  if (config_.event_period <= std::chrono::milliseconds::zero()) {
    return "the dashboard event period must be positive";
  }
  if (config_.token.empty() && !is_loopback_host(config_.host)) {
    return "refusing to listen on " + address +
           " without a token: set [http] token (anyone on the network could change what the "
           "vehicles receive), or listen on 127.0.0.1";
  }
  if (config_.max_connections_per_client == 0 ||
      config_.request_timeout <= std::chrono::milliseconds::zero() ||
      config_.idle_timeout <= std::chrono::milliseconds::zero()) {
    return "the dashboard connection limits must be positive";
  }
  install_routes();
  const std::size_t threads = std::max(config_.max_connections, config_.max_event_clients + 2);
  server_.new_task_queue = [threads] { return new ConnectionThreads(threads); };
  server_.set_payload_max_length(kMaxBodyBytes);
  // Timeouts between and within requests are LimitedServer's (config_.idle_timeout and
  // request_timeout); httplib's read timeout only remains on the socket as SO_RCVTIMEO.
  server_.set_read_timeout(config_.idle_timeout);
  // Not httplib's default options (socket_io.hpp says why).
  std::optional<detail::Socket> listen_socket;
  server_.set_socket_options([&listen_socket](socket_t sock) {
    detail::set_listen_options(static_cast<detail::Socket>(sock));
    listen_socket = static_cast<detail::Socket>(sock);
  });

  detail::clear_socket_error();
  int bound = -1;
  if (config_.port == 0) {
    bound = server_.bind_to_any_port(config_.host);
  } else if (server_.bind_to_port(config_.host, config_.port)) {
    bound = config_.port;
  }
  if (bound <= 0) {
    // httplib reports only failure; the socket error still holds the reason from getaddrinfo/bind.
    const std::string error = detail::last_socket_error();
    return "cannot listen on " + address + ": " +
           (!error.empty() ? error
                           : std::string("address not available or host name does not resolve"));
  }
  // httplib listens with a backlog of 5: a few idle connections waiting for accept() made the
  // kernel drop new handshakes, and the operator's browser retried after 1, 3, 7 s. Listening
  // again on the bound socket only raises the backlog.
  if (listen_socket) detail::raise_backlog(*listen_socket);
  port_ = static_cast<std::uint16_t>(bound);
  started_ = true;
  thread_ = std::thread([this] { server_.listen_after_bind(); });
  // stop() only takes effect once the accept loop runs; wait for it so a quick stop() after
  // start() cannot be lost. The socket already accepts connections (bound and listening).
  while (!server_.is_running() && thread_.joinable()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  spdlog::info("dashboard: http://{}:{}/", host_for_url(config_.host), port_);
  return std::nullopt;
}

void DashboardServer::Impl::stop() {
  {
    std::lock_guard lock(stop_mutex_);
    stopping_ = true;
  }
  stop_cv_.notify_all();
  if (thread_.joinable()) {
    server_.stop();
    thread_.join();
  }
}

bool DashboardServer::Impl::check_host(const httplib::Request& req, httplib::Response& res) {
  if (!config_.token.empty() && config_.allowed_hosts.empty()) return true;
  // RFC 9112 §3.2: a request with no Host or more than one is answered 400 by the standard; 403
  // here, with the same JSON as a foreign Host, since nothing else about it is wrong.
  const bool one_host = req.get_header_value_count("Host") == 1;
  const std::string host = req.get_header_value("Host");
  if (one_host && host_allowed(host, port_, config_.allowed_hosts)) return true;
  const std::string message =
      host_refusal(one_host ? std::optional<std::string_view>(host) : std::nullopt);
  const std::uint64_t refused = ++host_refused_;
  if (is_power_of_ten(refused)) {  // a rebinding page or a scanner loops
    spdlog::warn("dashboard: {} ({} refused so far)", message, refused);
  }
  res.set_header("Connection", "close");  // any request body is left unread
  send_error(res, ApiError{403, message, ""});
  return false;
}

httplib::Server::HandlerResponse DashboardServer::Impl::check_access(const httplib::Request& req,
                                                                     httplib::Response& res) {
  using httplib::Server;
  // Before anything else, for every path (page files and /api/events included): nothing is read
  // or changed for a request that does not name this server.
  if (!check_host(req, res)) return Server::HandlerResponse::Handled;
  // The page itself is public: it holds no data, and a browser cannot attach a header to a page
  // load. Everything under /api/ is guarded.
  if (req.path.rfind("/api/", 0) != 0 && req.path != "/api")
    return Server::HandlerResponse::Unhandled;
  const bool mutating = req.method == "POST" || req.method == "PATCH" || req.method == "DELETE" ||
                        req.method == "PUT";
  if (!config_.token.empty() &&
      !bearer_token_matches(req.get_header_value("Authorization"), config_.token)) {
    res.set_header("WWW-Authenticate", "Bearer realm=\"mocaplink\"");
    res.set_header("Connection", "close");  // any request body is left unread
    send_error(res,
               ApiError{401, "missing or wrong token: send Authorization: Bearer <token>", ""});
    return Server::HandlerResponse::Handled;
  }
  if (mutating && !origin_allowed(req.get_header_value("Origin"), req.get_header_value("Host"))) {
    res.set_header("Connection", "close");
    send_error(res, ApiError{403, "cross-origin request refused", ""});
    return Server::HandlerResponse::Handled;
  }
  // A JSON content type forces a CORS preflight on cross-site requests (which we never approve),
  // so a web page elsewhere cannot post a "simple" form request to a loopback dashboard.
  if ((req.method == "POST" || req.method == "PATCH") &&
      !is_json_content_type(req.get_header_value("Content-Type"))) {
    res.set_header("Connection", "close");
    send_error(res, ApiError{415, "Content-Type must be application/json", ""});
    return Server::HandlerResponse::Handled;
  }
  return Server::HandlerResponse::Unhandled;
}

std::shared_ptr<const DashboardServer::Impl::Snapshot> DashboardServer::Impl::snapshot() {
  std::lock_guard lock(snapshot_mutex_);
  const auto now = Clock::now();
  // Many clients share one backend call per half period.
  if (snapshot_ && now - snapshot_time_ < config_.event_period / 2) return snapshot_;
  StatusView status = backend_.status();
  alerts_.annotate(status, std::chrono::duration<double>(now - created_).count());
  status.http = server_.counters();
  status.http.host_refused = host_refused_.load();
  auto fresh = std::make_shared<Snapshot>();
  fresh->status = status;
  fresh->text = fresh->status.dump();
  snapshot_ = fresh;
  snapshot_time_ = now;
  return snapshot_;
}

void DashboardServer::Impl::invalidate_snapshot() {
  std::lock_guard lock(snapshot_mutex_);
  snapshot_.reset();
}

void DashboardServer::Impl::respond_vehicle(httplib::Response& res, int status,
                                            const std::string& name, bool changed) {
  const auto snap = snapshot();
  for (const json& vehicle : snap->status.at("vehicles")) {
    if (vehicle.at("name") == name) {
      send_json(res, status, vehicle);
      return;
    }
  }
  if (changed) {
    send_json(res, status, json{{"name", name}});
    return;
  }
  send_error(res, ApiError{404, "no vehicle named \"" + name + "\"", ""});
}

void DashboardServer::Impl::apply_and_respond(httplib::Response& res, const VehicleChange& change,
                                              const std::string& name, int success_status) {
  if (auto error = backend_.apply(change)) {
    spdlog::debug("dashboard: change to {} refused: {}", name, error->error);
    send_error(res, *error);
    return;
  }
  invalidate_snapshot();
  if (success_status == 204) {
    res.status = 204;
    return;
  }
  // Only now: the backend has accepted the name (no control characters, A-Z a-z 0-9 _ . -).
  if (success_status == 201) res.set_header("Location", std::string(kVehiclePath) + name);
  respond_vehicle(res, success_status, name, true);
}

void DashboardServer::Impl::serve_events(httplib::Response& res) {
  if (event_clients_.fetch_add(1) >= config_.max_event_clients) {
    --event_clients_;
    send_error(res, ApiError{503, "too many event streams open", ""});
    return;
  }
  res.set_header("Cache-Control", "no-store");
  res.set_header("X-Accel-Buffering", "no");  // proxies: do not buffer the stream
  res.set_chunked_content_provider(
      "text/event-stream",
      [this, sequence = std::uint64_t{0}](std::size_t, httplib::DataSink& sink) mutable {
        if (stopping_) {
          sink.done();
          return true;
        }
        std::string event = sequence == 0 ? "retry: 1000\n" : "";
        event += "id: " + std::to_string(++sequence) + "\nevent: status\ndata: ";
        event += snapshot()->text;
        event += "\n\n";
        if (!sink.is_writable() || !sink.write(event.data(), event.size())) return false;
        std::unique_lock lock(stop_mutex_);
        stop_cv_.wait_for(lock, config_.event_period, [this] { return stopping_.load(); });
        return true;
      },
      [this](bool) { --event_clients_; });
}

void DashboardServer::Impl::install_routes() {
  using httplib::Request;
  using httplib::Response;
  server_.set_pre_routing_handler(
      [this](const Request& req, Response& res) { return check_access(req, res); });

  server_.Get("/api/status", [this](const Request&, Response& res) {
    const auto snap = snapshot();
    res.set_header("Cache-Control", "no-store");
    res.set_content(snap->text, "application/json");
  });
  server_.Get("/api/events", [this](const Request&, Response& res) { serve_events(res); });
  server_.Get("/api/vehicles", [this](const Request&, Response& res) {
    send_json(res, 200, snapshot()->status.at("vehicles"));
  });
  server_.Post("/api/vehicles", [this](const Request& req, Response& res) {
    auto add = parse_vehicle_spec(req.body);
    if (!add.ok()) return send_error(res, add.error());
    apply_and_respond(res, add.value(), add.value().name, 201);
  });

  const std::string vehicle_pattern = std::string(kVehiclePath) + "([^/]+)";
  // A name no vehicle has (whatever its spelling) is answered 404 by the snapshot or the backend.
  server_.Get(vehicle_pattern, [this](const Request& req, Response& res) {
    respond_vehicle(res, 200, req.matches[1]);
  });
  server_.Patch(vehicle_pattern, [this](const Request& req, Response& res) {
    const std::string name = req.matches[1];
    auto patch = parse_vehicle_patch(req.body, name);
    if (!patch.ok()) return send_error(res, patch.error());
    apply_and_respond(res, patch.value(), name, 200);
  });
  server_.Delete(vehicle_pattern, [this](const Request& req, Response& res) {
    const std::string name = req.matches[1];
    apply_and_respond(res, RemoveVehicle{name}, name, 204);
  });
  // The set-up list's fixes and the reboot: only ever on this request (docs/api.md).
  const std::string setup_pattern = vehicle_pattern + "/setup";
  server_.Post(setup_pattern, [this](const Request& req, Response& res) {
    const std::string name = req.matches[1];
    auto setup = parse_vehicle_setup(req.body, name);
    if (!setup.ok()) return send_error(res, setup.error());
    apply_and_respond(res, setup.value(), name, 200);
  });

  // Known paths with the wrong method: 405 with Allow.
  auto not_allowed = [](const char* allow) {
    return [allow](const Request&, Response& res) { send_method_not_allowed(res, allow); };
  };
  for (const char* path : {"/api/status", "/api/events"}) {
    server_.Post(path, not_allowed("GET"));
    server_.Put(path, not_allowed("GET"));
    server_.Patch(path, not_allowed("GET"));
    server_.Delete(path, not_allowed("GET"));
  }
  server_.Put("/api/vehicles", not_allowed("GET, POST"));
  server_.Patch("/api/vehicles", not_allowed("GET, POST"));
  server_.Delete("/api/vehicles", not_allowed("GET, POST"));
  server_.Post(vehicle_pattern, not_allowed("GET, PATCH, DELETE"));
  server_.Put(vehicle_pattern, not_allowed("GET, PATCH, DELETE"));
  server_.Get(setup_pattern, not_allowed("POST"));
  server_.Put(setup_pattern, not_allowed("POST"));
  server_.Patch(setup_pattern, not_allowed("POST"));
  server_.Delete(setup_pattern, not_allowed("POST"));

  server_.Get("/.*", [](const Request& req, Response& res) {
    const auto asset = find_asset(req.path);
    if (!asset) {
      res.status = 404;  // the error handler writes the body
      return;
    }
    res.set_header("Cache-Control", "no-cache");
    res.set_header("X-Content-Type-Options", "nosniff");
    res.set_header("Content-Security-Policy", kContentSecurityPolicy);
    res.set_content(reinterpret_cast<const char*>(asset->data.data()), asset->data.size(),
                    std::string(asset->content_type).c_str());
  });

  // Anything unmatched (and every error without a body) gets a JSON body under /api/.
  server_.set_error_handler([](const Request& req, Response& res) {
    if (!res.body.empty()) return;
    const std::string message = res.status == 404   ? "not found"
                                : res.status == 413 ? "request body too large"
                                : res.status == 400 ? "bad request"
                                                    : "request refused";
    if (req.path.rfind("/api", 0) == 0) {
      send_json(res, res.status, json{{"error", message}, {"field", ""}});
    } else {
      res.set_content(message + "\n", "text/plain");
    }
  });
}

DashboardServer::DashboardServer(DashboardBackend& backend, DashboardServerConfig config)
    : impl_(std::make_unique<Impl>(backend, std::move(config))) {}

DashboardServer::~DashboardServer() = default;

std::optional<std::string> DashboardServer::start() {
  return impl_->start();
}

std::uint16_t DashboardServer::port() const {
  return impl_->port();
}

void DashboardServer::stop() {
  impl_->stop();
}

}  // namespace mocaplink::web
