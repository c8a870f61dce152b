// NatNet unicast as Motive does it (docs/sources.md "Where unicast frames come from"): Motive sends
// unicast frames from its data port to the endpoint the client's NAT_CONNECT came from, expires a
// client after about 10 s without NAT_KEEPALIVE (NAT_DISCONNECTBYTIMEOUT), answers
// NAT_ECHOREQUEST but not NAT_KEEPALIVE, and a "Bitstream,X.Y" request changes the bitstream of
// the client that asked alone. Three sides on real sockets on 127.0.0.1:
//   - the natnet:// client against a scripted server whose frames come from chosen endpoints;
//   - the emulator against a raw client built from the codecs;
//   - the natnet:// client reading the emulator while a second client switches to 3.1, and
//     against a scripted server that switches the client's own bitstream with and without the
//     §4.7 flag.
// Readiness is awaited on conditions; the only timed waits are bounded polls for something that
// must not arrive, which never make a failure pass.
#include <poll.h>

#include <condition_variable>
#include <mutex>

#include <gtest/gtest.h>

#include "mocaplink/wire/natnet_packet.hpp"
#include "natnet_test_support.hpp"

namespace mocaplink::sources {
namespace {

namespace nn = wire::natnet;
using asio::ip::udp;
using Bytes = std::vector<std::byte>;
using test::Collector;
using test::Event;

const auto kLoopback = asio::ip::address_v4::loopback();

Bytes frame_packet(std::int32_t number, nn::Version v, std::uint16_t params = 0) {
  nn::FrameOfData f;
  f.frame_number = number;
  nn::RigidBodySample rb;
  rb.id = 7;
  rb.position = {1.0f, 2.0f, static_cast<float>(number)};
  rb.params = 1;
  f.rigid_bodies.push_back(rb);
  f.timestamp_s = number * 0.005;
  f.mid_exposure_ticks = 1000;
  f.transmit_ticks = 1500;
  f.params = params;
  return nn::encode_frame(f, v);
}

std::vector<std::uint64_t> frame_numbers(const std::vector<Event>& events) {
  std::vector<std::uint64_t> out;
  for (const auto& e : events) {
    if (e.is_frame) out.push_back(e.frame.frame_number);
  }
  return out;
}

// A Motive stand-in with a command socket and a data socket, driven by the test: it answers
// NAT_CONNECT (server info: unicast, its data port, the current version), NAT_REQUEST_MODELDEF
// (rigid body "Quad", id 7) and "Bitstream"; frames are sent by the test (send_frames) or, with
// rate_hz, streamed from the data socket to the client at that rate.
class ScriptedServer {
 public:
  explicit ScriptedServer(nn::Version version, double rate_hz = 0.0)
      : version_(version), rate_hz_(rate_hz) {
    receive();
    if (rate_hz_ > 0.0) tick();
    thread_ = std::thread([this] { io_.run(); });
  }
  ~ScriptedServer() {
    io_.stop();
    if (thread_.joinable()) thread_.join();
  }
  std::uint16_t port() const { return command_.local_endpoint().port(); }
  std::uint16_t data_port() const { return data_.local_endpoint().port(); }

  /// Blocks until the client asked for the model definitions; returns its command endpoint.
  udp::endpoint wait_for_model_request() {
    std::unique_lock lock(mutex_);
    cv_.wait_for(lock, test::kWaitCap, [&] { return model_requests_ > 0; });
    return client_;
  }
  int connects() {
    std::lock_guard lock(mutex_);
    return connects_;
  }
  /// From frame `at` on, frames are sent in `v`; the first three carry `flag` (0 = no flag).
  void switch_version_at(std::int32_t at, nn::Version v, std::uint16_t flag) {
    asio::post(io_, [=, this] {
      switch_at_ = at;
      switch_to_ = v;
      switch_flag_ = flag;
    });
  }
  /// Sends frames `first`… from `from` (one of this server's sockets, or another) to `to`.
  static void send_frames(udp::socket& from, const udp::endpoint& to, std::int32_t first, int count,
                          nn::Version v) {
    for (int i = 0; i < count; ++i) {
      asio::error_code ignored;
      from.send_to(asio::buffer(frame_packet(first + i, v)), to, 0, ignored);
    }
  }
  udp::socket& command_socket() { return command_; }
  udp::socket& data_socket() { return data_; }

 private:
  void receive() {
    command_.async_receive_from(asio::buffer(buffer_), from_,
                                [this](const asio::error_code& ec, std::size_t n) {
                                  if (ec == asio::error::operation_aborted) return;
                                  if (!ec) on_request(std::span(buffer_.data(), n));
                                  receive();
                                });
  }

  void on_request(std::span<const std::byte> bytes) {
    auto packet = nn::split_packet(bytes);
    if (!packet) return;
    asio::error_code ignored;
    switch (static_cast<nn::MessageId>(packet.value().id)) {
      case nn::MessageId::connect: {
        nn::ServerInfo info;
        info.sender.name = "Scripted";
        info.sender.natnet_version = {version_.major, version_.minor, 0, 0};
        info.has_connection_info = true;
        info.clock_hz = 1000;
        info.data_port = data_port();
        info.multicast = false;
        command_.send_to(asio::buffer(nn::encode_server_info(info)), from_, 0, ignored);
        std::lock_guard lock(mutex_);
        ++connects_;
        return;
      }
      case nn::MessageId::request_model_def: {
        nn::ModelDefinitions defs;
        nn::RigidBodyDescription rb;
        rb.name = "Quad";
        rb.id = 7;
        defs.rigid_bodies.push_back(rb);
        command_.send_to(asio::buffer(nn::encode_model_definitions(defs, version_)), from_, 0,
                         ignored);
        {
          std::lock_guard lock(mutex_);
          ++model_requests_;
          client_ = from_;
        }
        cv_.notify_all();
        return;
      }
      case nn::MessageId::request: {
        auto text = nn::parse_string_payload(packet.value().payload);
        if (text && text.value() == "Bitstream") {
          // As Motive seems to send it, without a NUL (nn::encode_response_text).
          command_.send_to(
              asio::buffer(nn::encode_response_text("Bitstream," + version_.to_string() + ".0")),
              from_, 0, ignored);
        }
        return;
      }
      default:
        return;
    }
  }

  void tick() {
    timer_.expires_after(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(1.0 / rate_hz_)));
    timer_.async_wait([this](const asio::error_code& ec) {
      if (ec) return;
      udp::endpoint to;
      {
        std::lock_guard lock(mutex_);
        to = client_;
      }
      if (to.port() != 0) {
        std::uint16_t params = 0;
        if (switch_at_ > 0 && next_frame_ >= switch_at_) {
          version_ = switch_to_;
          if (next_frame_ < switch_at_ + 3) params = switch_flag_;
        }
        asio::error_code ignored;
        data_.send_to(asio::buffer(frame_packet(next_frame_++, version_, params)), to, 0, ignored);
      }
      tick();
    });
  }

  nn::Version version_;
  double rate_hz_;
  asio::io_context io_;
  udp::socket command_{io_, udp::endpoint(kLoopback, 0)};
  udp::socket data_{io_, udp::endpoint(kLoopback, 0)};
  asio::steady_timer timer_{io_};
  udp::endpoint from_;
  std::vector<std::byte> buffer_ = std::vector<std::byte>(nn::kMaxDatagramBytes);
  std::int32_t next_frame_ = 1;
  std::int32_t switch_at_ = 0;
  nn::Version switch_to_;
  std::uint16_t switch_flag_ = 0;
  std::mutex mutex_;
  std::condition_variable cv_;
  int connects_ = 0;
  int model_requests_ = 0;
  udp::endpoint client_;
  std::thread thread_;
};

NatnetSourceOptions unicast_client(std::uint16_t port) {
  NatnetSourceOptions o = test::natnet_client(port);
  o.target.transport = NatnetTransport::unicast;
  return o;
}

bool has_frame(const std::vector<Event>& events, std::uint64_t number) {
  return std::any_of(events.begin(), events.end(),
                     [&](const Event& e) { return e.is_frame && e.frame.frame_number == number; });
}

// --- the client: where unicast frames may come from ---------------------------------------------

// The natnet:// client connected in unicast to a scripted server that sends no frame by itself.
struct ConnectedClient {
  ScriptedServer server{{4, 1}};
  NatnetSource client{unicast_client(server.port()), "natnet://scripted"};
  Collector got;
  udp::endpoint to;  ///< the client's command socket, where the server registered it

  ConnectedClient() {
    client.start(got.frame_sink(), got.state_sink());
    to = server.wait_for_model_request();
    EXPECT_NE(to.port(), 0);
    EXPECT_TRUE(got.wait([](const std::vector<Event>& events) {
      return std::any_of(events.begin(), events.end(), [](const Event& e) {
        return !e.is_frame && e.state == SourceState::connected;
      });
    }));
  }
  /// Waits for frame `number` to be delivered, then stops the client.
  void finish_at(std::uint64_t number) {
    EXPECT_TRUE(got.wait([number](const std::vector<Event>& e) { return has_frame(e, number); }))
        << client.last_error();
    client.stop();
  }
};

TEST(NatnetUnicastClient, FramesFromTheServersDataPortAreRead) {
  ConnectedClient c;
  ScriptedServer::send_frames(c.server.data_socket(), c.to, 1, 10, {4, 1});
  c.finish_at(10);
  EXPECT_EQ(frame_numbers(c.got.events()).size(), 10u);
  EXPECT_EQ(c.client.natnet_counters().foreign_datagrams.load(), 0u);
  EXPECT_EQ(c.client.natnet_counters().frames_from_command_port.load(), 0u);
}

// Motive never sends frames from its command port, and OptiTrack's library drops them; the
// endpoint is the server's own, so mocaplink reads them and counts them.
TEST(NatnetUnicastClient, FramesFromTheServersCommandPortAreReadAndCounted) {
  ConnectedClient c;
  ScriptedServer::send_frames(c.server.command_socket(), c.to, 1, 10, {4, 1});
  c.finish_at(10);
  EXPECT_EQ(frame_numbers(c.got.events()).size(), 10u);
  EXPECT_EQ(c.client.natnet_counters().frames_from_command_port.load(), 10u);
}

TEST(NatnetUnicastClient, FramesFromAnotherHostOrPortAreForeign) {
  ConnectedClient c;
  asio::io_context io;
  // Another host (127.0.0.2 is on the loopback interface too) from the server's data port number,
  // and the server's own address from a third port.
  udp::socket other_host(io, udp::v4());
  asio::error_code ec;
  other_host.set_option(udp::socket::reuse_address(true));
  other_host.bind(udp::endpoint(asio::ip::make_address_v4("127.0.0.2"), c.server.data_port()), ec);
  ASSERT_FALSE(ec) << ec.message();
  udp::socket other_port(io, udp::endpoint(kLoopback, 0));
  ScriptedServer::send_frames(other_host, c.to, 1, 5, {4, 1});
  ScriptedServer::send_frames(other_port, c.to, 6, 5, {4, 1});
  ScriptedServer::send_frames(c.server.data_socket(), c.to, 11, 1, {4, 1});  // then a real one
  c.finish_at(11);
  EXPECT_EQ(frame_numbers(c.got.events()), std::vector<std::uint64_t>{11});
  EXPECT_EQ(c.client.natnet_counters().foreign_datagrams.load(), 10u);
}

// --- the emulator: what a client sees of it -----------------------------------------------------

// A raw NatNet client on 127.0.0.1: sends from one socket, records what arrives and from where.
class RawClient {
 public:
  RawClient() : socket_(io_, udp::endpoint(kLoopback, 0)) {}
  void send(const Bytes& packet, std::uint16_t server_port) {
    socket_.send_to(asio::buffer(packet), udp::endpoint(kLoopback, server_port));
  }
  void connect(std::uint16_t server_port) {
    nn::ConnectRequest req;
    req.sender.name = "raw";
    req.sender.natnet_version = {4, 1, 0, 0};
    send(nn::encode_connect(req), server_port);
  }
  struct Datagram {
    std::uint16_t id = 0;
    udp::endpoint from;
    Bytes bytes;
  };
  /// The next datagram, or nothing within `cap` (a bound for what may not come).
  std::optional<Datagram> next(std::chrono::milliseconds cap = test::kWaitCap) {
    pollfd p{socket_.native_handle(), POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(cap.count())) != 1) return std::nullopt;
    Bytes buf(nn::kMaxDatagramBytes);
    udp::endpoint from;
    asio::error_code ec;
    const std::size_t n = socket_.receive_from(asio::buffer(buf), from, 0, ec);
    if (ec || n < 4) return std::nullopt;
    buf.resize(n);
    const auto id = static_cast<std::uint16_t>(std::to_integer<unsigned>(buf[0]) |
                                               (std::to_integer<unsigned>(buf[1]) << 8));
    return Datagram{id, from, buf};
  }
  /// The next datagram with message id `id`, skipping others (frames, typically).
  std::optional<Datagram> next_of(nn::MessageId id) {
    for (int i = 0; i < 10000; ++i) {
      auto d = next();
      if (!d) return std::nullopt;
      if (d->id == static_cast<std::uint16_t>(id)) return d;
    }
    return std::nullopt;
  }

 private:
  asio::io_context io_;
  udp::socket socket_;
};

nn::FrameOfData parse_frame_in(const RawClient::Datagram& d, nn::Version v) {
  auto packet = nn::split_packet(d.bytes);
  EXPECT_TRUE(packet);
  auto frame = nn::parse_frame(packet.value().payload, v);
  EXPECT_TRUE(frame) << "not a " << v.to_string() << " frame";
  return frame ? frame.value() : nn::FrameOfData{};
}

TEST(NatnetEmulatorUnicast, FramesLeaveFromTheDataPortToTheConnectingEndpoint) {
  auto server = test::start_natnet_server(test::unicast_server());
  ASSERT_NE(server->data_port(), server->port());
  RawClient raw;
  raw.connect(server->port());
  const auto info = raw.next_of(nn::MessageId::server_info);
  ASSERT_TRUE(info);
  EXPECT_EQ(info->from.port(), server->port());  // replies come from the command port
  const auto parsed = nn::parse_server_info(nn::split_packet(info->bytes).value().payload);
  ASSERT_TRUE(parsed);
  EXPECT_FALSE(parsed.value().multicast);
  EXPECT_EQ(parsed.value().data_port, server->data_port());  // announced as Motive does
  for (int i = 0; i < 20; ++i) {
    const auto d = raw.next_of(nn::MessageId::frame_of_data);
    ASSERT_TRUE(d);
    EXPECT_EQ(d->from, udp::endpoint(kLoopback, server->data_port()));
  }
  // An echo request is answered (from the command port); a keep-alive is not answered at all.
  raw.send(nn::encode_empty(nn::MessageId::keep_alive), server->port());
  Bytes echo = nn::encode_packet(nn::MessageId::echo_request, Bytes(8, std::byte{0x2a}));
  raw.send(echo, server->port());
  std::size_t frames = 0;
  for (;;) {
    const auto d = raw.next();
    ASSERT_TRUE(d);
    if (d->id == static_cast<std::uint16_t>(nn::MessageId::frame_of_data)) {
      ++frames;
      continue;
    }
    // The first non-frame is the echo response: nothing answered the keep-alive sent before.
    ASSERT_EQ(d->id, static_cast<std::uint16_t>(nn::MessageId::echo_response));
    EXPECT_EQ(d->from.port(), server->port());
    EXPECT_EQ(d->bytes.size(), 20u);
    break;
  }
  server->stop();
}

TEST(NatnetEmulatorUnicast, AClientWithoutKeepAliveGetsDisconnectByTimeout) {
  auto so = test::unicast_server();
  so.keepalive_timeout = std::chrono::milliseconds(1000);
  auto server = test::start_natnet_server(so);
  RawClient raw;
  raw.connect(server->port());
  ASSERT_TRUE(raw.next_of(nn::MessageId::server_info));
  // A keep-alive every 5 frames (25 ms at 200 Hz) for 1.5 s: still served.
  for (int i = 0; i < 300; ++i) {
    if (i % 5 == 0) raw.send(nn::encode_empty(nn::MessageId::keep_alive), server->port());
    ASSERT_TRUE(raw.next_of(nn::MessageId::frame_of_data));
  }
  EXPECT_EQ(server->counters().clients_timed_out.load(), 0u);
  // Then only NAT_CONNECTs, every 5 frames, which do not keep a session alive: the server ends
  // it (within 10 s of frames: a bound that only a failure reaches).
  std::optional<RawClient::Datagram> bye;
  for (int i = 0; i < 2000 && !bye; ++i) {
    if (i % 5 == 0) raw.connect(server->port());
    auto d = raw.next();
    ASSERT_TRUE(d);
    if (d->id == static_cast<std::uint16_t>(nn::MessageId::disconnect_by_timeout)) bye = d;
  }
  ASSERT_TRUE(bye) << "still served without keep-alives";
  EXPECT_EQ(bye->bytes.size(), 4u);
  EXPECT_EQ(server->counters().clients_timed_out.load(), 1u);
  EXPECT_EQ(server->counters().clients_now.load(), 0u);
  // No frame follows (bounded wait for an absence), unless a NAT_CONNECT sent before the end
  // arrived after it and started a new session, which its server info announces first.
  while (const auto after = raw.next(std::chrono::milliseconds(100))) {
    if (after->id == static_cast<std::uint16_t>(nn::MessageId::server_info)) break;
    ADD_FAILURE() << "message " << after->id << " after the session ended";
    break;
  }
  server->stop();
}

TEST(NatnetEmulatorUnicast, BitstreamChangesOnlyForTheClientThatAsked) {
  auto server = test::start_natnet_server(test::unicast_server());
  RawClient a;
  RawClient b;
  RawClient stranger;
  a.connect(server->port());
  b.connect(server->port());
  ASSERT_TRUE(a.next_of(nn::MessageId::server_info));
  ASSERT_TRUE(b.next_of(nn::MessageId::server_info));
  // A host that never connected is not answered, and changes nothing.
  stranger.send(nn::encode_string_packet(nn::MessageId::request, "Bitstream,3.1"), server->port());
  b.send(nn::encode_string_packet(nn::MessageId::request, "Bitstream,3.1"), server->port());
  const auto ok = b.next_of(nn::MessageId::response);
  ASSERT_TRUE(ok);
  EXPECT_EQ(ok->bytes, (Bytes{std::byte{3}, std::byte{0}, std::byte{4}, std::byte{0}, std::byte{0},
                              std::byte{0}, std::byte{0}, std::byte{0}}));
  // b's frames are 3.1 from now on, the first ones flagged "bitstream changed" (§4.7 0x08).
  std::optional<RawClient::Datagram> d;
  for (;;) {
    d = b.next_of(nn::MessageId::frame_of_data);
    ASSERT_TRUE(d);
    auto packet = nn::split_packet(d->bytes).value();
    if (nn::parse_frame(packet.payload, {3, 1})) break;
  }
  EXPECT_NE(parse_frame_in(*d, {3, 1}).params & nn::kParamBitstreamChanged, 0);
  b.send(nn::encode_string_packet(nn::MessageId::request, "Bitstream"), server->port());
  const auto query = b.next_of(nn::MessageId::response);
  ASSERT_TRUE(query);
  // The text alone, no NUL: OptiTrack's Python client 4.1 parses the rest of the datagram as
  // "Bitstream,X.Y.Z" and fails on a NUL ("invalid literal for int(): '0\x00'").
  const auto reply = nn::split_packet(query->bytes).value().payload;
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(reply.data()), reply.size()),
            "Bitstream,3.1.0");
  // a still gets 4.1, never flagged; its model definitions are 4.1 too.
  for (int i = 0; i < 20; ++i) {
    const auto fa = a.next_of(nn::MessageId::frame_of_data);
    ASSERT_TRUE(fa);
    EXPECT_EQ(parse_frame_in(*fa, {4, 1}).params & nn::kParamBitstreamChanged, 0);
  }
  a.send(nn::encode_empty(nn::MessageId::request_model_def), server->port());
  const auto defs = a.next_of(nn::MessageId::model_def);
  ASSERT_TRUE(defs);
  EXPECT_TRUE(nn::parse_model_definitions(nn::split_packet(defs->bytes).value().payload, {4, 1}));
  // The stranger got nothing: its request was refused, no reply.
  EXPECT_EQ(server->counters().requests_refused.load(), 1u);
  EXPECT_FALSE(stranger.next(std::chrono::milliseconds(100)));
  server->stop();
}

// --- bitstream changes, end to end ---------------------------------------------------------------

// issue 27 0b: another client switching to 3.1 while mocaplink reads costs mocaplink nothing.
TEST(NatnetBitstream, AnotherClientSwitchingTo31CostsNoFrames) {
  auto server = test::start_natnet_server(test::unicast_server());
  NatnetSource client(test::natnet_client(server->port()), "natnet://test");
  Collector got;
  client.start(got.frame_sink(), got.state_sink());
  ASSERT_TRUE(got.wait_frames(20));
  RawClient other;
  other.connect(server->port());
  ASSERT_TRUE(other.next_of(nn::MessageId::server_info));
  other.send(nn::encode_string_packet(nn::MessageId::request, "Bitstream,3.1"), server->port());
  ASSERT_TRUE(other.next_of(nn::MessageId::response));
  const std::size_t at_switch = Collector::frame_count(got.events());
  ASSERT_TRUE(got.wait_frames(at_switch + 100)) << client.last_error();
  client.stop();
  server->stop();
  const auto numbers = frame_numbers(got.events());
  for (std::size_t i = 1; i < numbers.size(); ++i) {
    EXPECT_EQ(numbers[i], numbers[i - 1] + 1) << "frames lost after " << numbers[i - 1];
  }
  EXPECT_EQ(client.counters().malformed.load(), 0u);
  EXPECT_EQ(client.counters().reconnects.load(), 0u);
}

// The client's own bitstream changes (its host asked, or Motive changed it): with the §4.7 flag or
// without it (frames stop decoding), the client re-reads the server info and model definitions at
// once and loses a few frames, not the 3 s of its silence timeout.
struct Switch {
  nn::Version to;
  std::uint16_t flag;  ///< §4.7 bit set on the first three frames of the new version, or 0
  const char* name;
};

class NatnetOwnBitstream : public ::testing::TestWithParam<Switch> {};

TEST_P(NatnetOwnBitstream, ASwitchCostsAFewFrames) {
  ScriptedServer server({4, 1}, test::kRateHz);
  auto co = unicast_client(server.port());
  co.silence_timeout = std::chrono::milliseconds(3000);  // the default: a reconnect would show
  NatnetSource client(co, "natnet://scripted");
  Collector got;
  client.start(got.frame_sink(), got.state_sink());
  ASSERT_TRUE(got.wait_frames(10)) << client.last_error();
  const auto first = frame_numbers(got.events()).front();
  const auto at = static_cast<std::int32_t>(first + 40);
  server.switch_version_at(at, GetParam().to, GetParam().flag);
  ASSERT_TRUE(got.wait([&](const std::vector<Event>& e) {
    return has_frame(e, static_cast<std::uint64_t>(at) + 100);
  })) << client.last_error();
  client.stop();
  const auto numbers = frame_numbers(got.events());
  std::uint64_t lost = 0;
  for (std::size_t i = 1; i < numbers.size(); ++i) lost += numbers[i] - numbers[i - 1] - 1;
  EXPECT_LE(lost, 5u) << "frames lost across the switch";
  EXPECT_EQ(client.counters().reconnects.load(), 0u);
  // The new version was noticed and the model definitions read again in it.
  EXPECT_EQ(client.natnet_counters().bitstream_changes.load(), 1u);
  EXPECT_EQ(client.natnet_counters().model_reloads.load(), 2u);
  for (const auto& e : got.events()) {
    if (e.is_frame) {
      EXPECT_FLOAT_EQ(static_cast<float>(e.frame.bodies.at(0).p_world_m.z()),
                      static_cast<float>(e.frame.frame_number));
    }
  }
}

// 4.1 → 3.1: the frame layout changes, so the frames stop decoding (whether flagged or not: the
// flag is in a frame the old layout cannot read). 4.1 → 4.2: frames still decode, only the model
// definitions change; the flag is all that tells.
INSTANTIATE_TEST_SUITE_P(
    Switches, NatnetOwnBitstream,
    ::testing::Values(Switch{{3, 1}, 0, "To31FramesStopDecoding"},
                      Switch{{3, 1}, nn::kParamBitstreamChanged, "To31Flagged"},
                      Switch{{4, 2}, nn::kParamBitstreamChanged, "To42Flagged"}),
    [](const auto& p) { return std::string(p.param.name); });

}  // namespace
}  // namespace mocaplink::sources
