// QTM RT codec against qtm-rt.md: its worked hex examples (§8) parse and encode exactly, the
// Qualisys C++ SDK's 6D parameter fixture (MIT, data/qtm/6d.h) and the §5.1 example parse to the
// right body names, the column-by-column matrix and NaN rules of §4.3, and hostile input.
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "data/qtm/6d.h"
#include "mocaplink/wire/qtm_frame.hpp"
#include "mocaplink/wire/qtm_parameters.hpp"
#include "mocaplink/wire/qtm_protocol.hpp"
#include "mocaplink/wire/qtm_server_session.hpp"
#include "vicon_test_bytes.hpp"

namespace mocaplink::wire::qtm {
namespace {

using vicon::test::hex;

// §8 golden vectors.
const char* const kWelcomeHex =
    "230000000100000051544d20525420496e7465726661636520636f6e6e656374656400";
const char* const kVersionHex = "150000000100000056657273696f6e20312e313900";
const char* const kDataHex =
    "580000000300000040420f00000000002a000000010000004000000005000000010000000000000000007a4400"
    "00fac300007a430000803f0000000000000000000000000000803f0000000000000000000000000000803f";

std::vector<BodyParameters> named(std::initializer_list<const char*> names) {
  std::vector<BodyParameters> out;
  for (const char* n : names) out.push_back(BodyParameters{n, true, true});
  return out;
}

TEST(QtmGolden, WelcomeAndVersionCommandEncodeExactly) {
  EXPECT_EQ(ServerSession::welcome(), hex(kWelcomeHex));
  EXPECT_EQ(ServerSession::welcome().size(), 35u);
  EXPECT_EQ(encode_text(PacketType::command, "Version 1.19"), hex(kVersionHex));
  const auto bytes = hex(kWelcomeHex);
  const auto welcome = parse_packet(bytes, kDefaultMaxPacketBytes);
  ASSERT_TRUE(welcome);
  EXPECT_EQ(welcome.value().type, 1u);
  EXPECT_EQ(text_of(welcome.value().payload), "QTM RT Interface connected");
}

TEST(QtmGolden, DataPacketParsesAndEncodesExactly) {
  const auto bytes = hex(kDataHex);
  ASSERT_EQ(bytes.size(), 88u);
  const auto packet = parse_packet(bytes, kDefaultMaxPacketBytes);
  ASSERT_TRUE(packet);
  ASSERT_EQ(packet.value().type, 3u);
  const auto data = parse_data(packet.value().payload);
  ASSERT_TRUE(data) << data.error().reason;
  const DataPacket& d = data.value();
  EXPECT_EQ(d.timestamp_us, 1'000'000);
  EXPECT_EQ(d.frame_number, 42u);
  ASSERT_EQ(d.six_dof.size(), 1u);
  ASSERT_EQ(d.six_dof[0].type, Component::six_d);
  ASSERT_EQ(d.six_dof[0].bodies.size(), 1u);
  const Body6d& b = d.six_dof[0].bodies[0];
  EXPECT_EQ(b.position_mm, (std::array<float, 3>{1000.0f, -500.0f, 250.0f}));
  EXPECT_EQ(b.rotation, (std::array<float, 9>{1, 0, 0, 0, 1, 0, 0, 0, 1}));
  EXPECT_EQ(encode_data(d), bytes);

  const auto mapped = to_mocap_frame(d, Component::six_d, named({"Drone1"}), 100.0);
  ASSERT_TRUE(mapped);
  const core::MocapFrame& f = mapped.value().frame;
  EXPECT_EQ(f.frame_number, 42u);
  EXPECT_EQ(f.capture_time.time_since_epoch(), std::chrono::seconds(1));
  EXPECT_EQ(f.frame_rate_hz, 100.0);
  ASSERT_EQ(f.bodies.size(), 1u);
  EXPECT_EQ(f.bodies[0].name, "Drone1");
  EXPECT_TRUE(f.bodies[0].tracked);
  EXPECT_EQ(f.bodies[0].p_world_m, Eigen::Vector3d(1.0, -0.5, 0.25));
  EXPECT_NEAR(f.bodies[0].q_world_body.w(), 1.0, 1e-12);
}

TEST(QtmGolden, NaNBodiesAreUntrackedInBothSpellings) {
  for (const char* nan : {"0000c07f", "ffffffff"}) {
    std::string h = std::string(kDataHex).substr(0, 2 * 40);
    for (int i = 0; i < 12; ++i) h += nan;
    const auto bytes = hex(h);
    ASSERT_EQ(bytes.size(), 88u);
    const auto data = parse_data(std::span(bytes).subspan(8));
    ASSERT_TRUE(data);
    const auto mapped = to_mocap_frame(data.value(), Component::six_d, named({"B"}), {});
    ASSERT_TRUE(mapped);
    EXPECT_FALSE(mapped.value().frame.bodies[0].tracked);
    EXPECT_EQ(mapped.value().invalid_poses, 0u);
  }
}

TEST(QtmFrame, MatrixIsReadColumnByColumn) {
  // 90° about +z: R = [[0,−1,0],[1,0,0],[0,0,1]]; first column (0, 1, 0) first on the wire.
  DataPacket d;
  SixDof six;
  Body6d b;
  b.position_mm = {0, 0, 0};
  b.rotation = {0, 1, 0, -1, 0, 0, 0, 0, 1};
  six.bodies = {b};
  d.six_dof = {six};
  const auto mapped = to_mocap_frame(d, Component::six_d, named({"B"}), {});
  ASSERT_TRUE(mapped);
  const auto q = mapped.value().frame.bodies[0].q_world_body;
  const double s = std::sqrt(0.5);
  EXPECT_NEAR(std::abs(q.dot(Eigen::Quaterniond(s, 0, 0, s))), 1.0, 1e-6);
}

TEST(QtmFrame, NotARotationIsInvalidAndBodyCountMustMatch) {
  DataPacket d;
  SixDof six;
  Body6d b;
  b.rotation = {2, 0, 0, 0, 1, 0, 0, 0, 1};
  six.bodies = {b};
  d.six_dof = {six};
  const auto mapped = to_mocap_frame(d, Component::six_d, named({"B"}), {});
  ASSERT_TRUE(mapped);
  EXPECT_FALSE(mapped.value().frame.bodies[0].tracked);
  EXPECT_FALSE(mapped.value().frame.bodies[0].mirrored);  // not orthonormal: no reflection either
  EXPECT_EQ(mapped.value().invalid_poses, 1u);
  EXPECT_FALSE(to_mocap_frame(d, Component::six_d, named({"A", "B"}), {}));
  EXPECT_FALSE(to_mocap_frame(DataPacket{}, Component::six_d, {}, {}));
}

TEST(QtmFrame, AReflectionMatrixIsNamedMirrored) {
  // 90° about +z, then y flipped: columns (0, 1, 0), (1, 0, 0), (0, 0, 1) — orthonormal, det −1.
  DataPacket d;
  SixDof six;
  Body6d b;
  b.position_mm = {10, 20, 30};
  b.rotation = {0, 1, 0, 1, 0, 0, 0, 0, 1};
  six.bodies = {b};
  d.six_dof = {six};
  const auto mapped = to_mocap_frame(d, Component::six_d, named({"B"}), {});
  ASSERT_TRUE(mapped);
  EXPECT_FALSE(mapped.value().frame.bodies[0].tracked);
  EXPECT_TRUE(mapped.value().frame.bodies[0].mirrored);
  EXPECT_EQ(mapped.value().invalid_poses, 1u);
  // Euler angles are always a rotation: the same body as angles is tracked, never mirrored.
  b.euler_deg = {0, 0, 90};
  six.type = Component::six_d_euler;
  six.bodies = {b};
  d.six_dof = {six};
  const auto euler = to_mocap_frame(d, Component::six_d_euler, named({"B"}), {});
  ASSERT_TRUE(euler);
  EXPECT_TRUE(euler.value().frame.bodies[0].tracked);
  EXPECT_FALSE(euler.value().frame.bodies[0].mirrored);
}

TEST(QtmFrame, EulerIsQualisysStandardRollPitchYawAboutRotatedAxes) {
  // Roll 90° about x alone turns body y into world z.
  const Eigen::Quaterniond roll = quaternion_from_euler({90, 0, 0});
  EXPECT_LT((roll * Eigen::Vector3d::UnitY() - Eigen::Vector3d::UnitZ()).norm(), 1e-12);
  // Yaw 90° after pitch: R = Ry(30°)·Rz(90°) maps body x to Ry(30°)·y = y.
  const Eigen::Quaterniond py = quaternion_from_euler({0, 30, 90});
  EXPECT_LT((py * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm(), 1e-12);
  for (const auto& angles : {std::array<double, 3>{10, -20, 30}, {-170, 80, 5}, {0, 0, -90}}) {
    const auto back = euler_from_quaternion(quaternion_from_euler(angles));
    for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR(back[i], angles[i], 1e-9);
  }
}

TEST(QtmFrame, AllFourComponentsRoundTripThroughTheEmulatorsEncoding) {
  core::MocapFrame f;
  f.frame_number = 7;
  f.capture_time = core::SourceTime{std::chrono::microseconds(123456)};
  core::BodySample a;
  a.name = "A";
  a.tracked = true;
  a.p_world_m = {1.5, -2.25, 0.5};
  a.q_world_body = Eigen::Quaterniond(0.9, 0.1, -0.3, 0.2).normalized();
  core::BodySample gone;
  gone.name = "Gone";
  f.bodies = {a, gone};
  const ServedFrame served = served_frame(f);
  ServerSession session({});
  for (const auto c : {Component::six_d, Component::six_d_residual, Component::six_d_euler,
                       Component::six_d_euler_residual}) {
    const auto bytes = session.encode(served, {c});
    const auto data = parse_data(std::span(bytes).subspan(8));
    ASSERT_TRUE(data) << to_string(c);
    EXPECT_EQ(bytes.size(), 8 + 16 + 16 + 2 * body_bytes(c));
    const auto mapped = to_mocap_frame(data.value(), c, named({"A", "Gone"}), {});
    ASSERT_TRUE(mapped);
    const auto& g = mapped.value().frame;
    EXPECT_EQ(g.frame_number, 7u);
    EXPECT_EQ(g.capture_time, f.capture_time);
    EXPECT_LT((g.bodies[0].p_world_m - a.p_world_m).norm(), 1e-6) << to_string(c);
    EXPECT_NEAR(std::abs(g.bodies[0].q_world_body.dot(a.q_world_body)), 1.0, 1e-6);
    EXPECT_FALSE(g.bodies[1].tracked);
    if (has_residual(c)) {
      EXPECT_EQ(data.value().six_dof[0].bodies[0].residual, 0.5f);
    }
  }
}

TEST(QtmData, HostileSizesAreErrorsNotAllocations) {
  EXPECT_FALSE(parse_header(hex("07000000 01000000"), kDefaultMaxPacketBytes));
  EXPECT_FALSE(parse_header(hex("ffffff7f 03000000"), kDefaultMaxPacketBytes));
  EXPECT_FALSE(parse_header(hex("08000000"), kDefaultMaxPacketBytes));
  EXPECT_FALSE(parse_packet(hex("09000000 06000000"), kDefaultMaxPacketBytes));  // short datagram
  // A 6D component claiming 2^32−1 bodies in 16 bytes.
  EXPECT_FALSE(
      parse_data(hex("0000000000000000 01000000 01000000 10000000 05000000 ffffffff "
                     "00000000")));
  // Component size past the end; zero size; trailing bytes; truncated header.
  EXPECT_FALSE(parse_data(hex("0000000000000000 01000000 01000000 ff000000 05000000")));
  EXPECT_FALSE(parse_data(hex("0000000000000000 01000000 01000000 00000000 05000000")));
  EXPECT_FALSE(parse_data(hex("0000000000000000 00000000 00000000 aa")));
  EXPECT_FALSE(parse_data(hex("00000000")));
  // Unknown components are skipped and counted.
  const auto other =
      parse_data(hex("0000000000000000 01000000 01000000 0c000000 11000000 abcd0000"));
  ASSERT_TRUE(other);
  EXPECT_EQ(other.value().other_components, 1u);
  EXPECT_TRUE(other.value().six_dof.empty());
}

TEST(QtmParameters, TheCppSdkFixtureGivesItsSixBodiesInOrder) {
  const auto p = parse_parameters(qualisys_cpp_sdk::tests::data::Get6DSettingsTest);
  ASSERT_TRUE(p) << p.error().reason << " at " << p.error().offset;
  EXPECT_EQ(p.value().root, "QTM_Parameters_Ver_1.25");
  EXPECT_TRUE(p.value().has_6d);
  EXPECT_FALSE(p.value().declared_bodies.has_value());
  std::vector<std::string> names;
  for (const auto& b : p.value().bodies) {
    names.push_back(b.name);
    EXPECT_TRUE(b.enabled);
    EXPECT_TRUE(b.global);
  }
  EXPECT_EQ(names,
            (std::vector<std::string>{"refined", "Table", "Screen2", "Cup", "Phone", "Screen1"}));
  EXPECT_EQ(p.value().duplicate_name(), "");
}

// qtm-rt.md §5.1 (≤ 1.20), as the published example prints it (with The_6D closing).
constexpr const char* kOldFormat = R"(<?xml version="1.0"?>
<QTM_Parameters_Ver_1.19>
  <The_6D>
    <Bodies>2</Bodies>
    <Body>
      <Name>Body1</Name>
      <RGBColor>ffffff</RGBColor>
      <Point><X>1.0</X><Y>2.0</Y><Z>3.0</Z></Point>
    </Body>
    <Body>
      <Name>Drone &amp; Co &#x41;</Name>
      <RGBColor>00ff00</RGBColor>
    </Body>
    <Euler><First>Roll</First><Second>Pitch</Second><Third>Yaw</Third></Euler>
  </The_6D>
</QTM_Parameters_Ver_1.19>)";

TEST(QtmParameters, TheOldFormatWithBodiesCountAndEuler) {
  const auto p = parse_parameters(kOldFormat);
  ASSERT_TRUE(p) << p.error().reason;
  EXPECT_EQ(p.value().declared_bodies, 2u);
  ASSERT_EQ(p.value().bodies.size(), 2u);
  EXPECT_EQ(p.value().bodies[0].name, "Body1");
  EXPECT_EQ(p.value().bodies[1].name, "Drone & Co A");
  EXPECT_EQ(p.value().euler_names, (std::array<std::string, 3>{"Roll", "Pitch", "Yaw"}));
}

TEST(QtmParameters, GeneralFrequencyEnabledAndRelativeBodies) {
  const auto p = parse_parameters(
      "<QTM_Parameters_Ver_1.24><General><Frequency>150</Frequency>"
      "<EulerAngles First='Yaw' Second='Pitch' Third='Roll'/></General><The_6D>"
      "<Body><Name>A</Name><Enabled>false</Enabled></Body>"
      "<Body><Name><![CDATA[B<1>]]></Name><Data_origin Relative_body='2'>2</Data_origin></Body>"
      "<Body><Name>A</Name></Body></The_6D></QTM_Parameters_Ver_1.24>");
  ASSERT_TRUE(p) << p.error().reason;
  EXPECT_EQ(p.value().frequency_hz, 150.0);
  EXPECT_EQ(p.value().euler_names[0], "Yaw");
  ASSERT_EQ(p.value().bodies.size(), 3u);
  EXPECT_FALSE(p.value().bodies[0].enabled);
  EXPECT_EQ(p.value().bodies[1].name, "B<1>");
  EXPECT_FALSE(p.value().bodies[1].global);
  EXPECT_EQ(p.value().duplicate_name(), "A");
}

TEST(QtmParameters, MalformedXmlIsAnError) {
  for (const char* bad :
       {"", "<a>", "<a></b>", "<a><b></a>", "<a x=1></a>", "<a>&bogus;</a>", "<a>&#0;</a>",
        "<a/><b/>", "<!-- x", "<a><The_6D><Body></Body></The_6D></a>",
        "<a><The_6D><Bodies>3</Bodies><Body><Name>x</Name></Body></The_6D></a>",
        "<a><The_6D><Bodies>many</Bodies></The_6D></a>", "text<a/>"}) {
    EXPECT_FALSE(parse_parameters(bad)) << bad;
  }
  std::string deep;
  for (int i = 0; i < 100; ++i) deep += "<a>";
  EXPECT_FALSE(parse_parameters(deep));
}

TEST(QtmParameters, TheEmulatorsXmlParsesBackInBothFormats) {
  const std::vector<std::string> names = {"Body1", "x&y<z>", "Body3"};
  for (const int minor : {18, 19, 20, 21, 24, 28}) {
    const std::string xml = encode_parameters(names, minor, {true, true}, 200.0);
    const auto p = parse_parameters(xml);
    ASSERT_TRUE(p) << minor << ": " << p.error().reason;
    EXPECT_EQ(p.value().declared_bodies.has_value(), minor < 21);
    EXPECT_EQ(p.value().frequency_hz, 200.0);
    ASSERT_EQ(p.value().bodies.size(), 3u);
    for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(p.value().bodies[i].name, names[i]);
  }
}

// Sends `text` as a client command and returns the replies.
Packets ask(ServerSession& s, const std::string& text, const std::vector<std::string>& names = {},
            const ServedFrame* latest = nullptr, bool nul = false) {
  const auto packet = encode_text(PacketType::command, text, nul);
  return s.on_client_packet(1, std::span(packet).subspan(8), names, latest);
}

std::string reply_text(const Packets& p, std::uint32_t type = 1) {
  if (p.size() != 1) return "<" + std::to_string(p.size()) + " packets>";
  const auto v = parse_packet(p[0], kDefaultMaxPacketBytes);
  if (!v || v.value().type != type) return "<other type>";
  return text_of(v.value().payload);
}

TEST(QtmServerSession, VersionNegotiationAndInfoCommands) {
  ServerSession s({.max_minor = 21});
  EXPECT_EQ(reply_text(ask(s, "Version")), "Version is 1.1");
  EXPECT_EQ(reply_text(ask(s, "Version 1.28")), "Version NOT supported");
  EXPECT_EQ(reply_text(ask(s, "version 1.21", {}, nullptr, true)), "Version set to 1.21");
  EXPECT_EQ(s.minor(), 21);
  EXPECT_EQ(reply_text(ask(s, "ByteOrder")), "Byte order is little endian");
  EXPECT_EQ(reply_text(ask(s, "QTMVersion")), "QTM Version is 0.0 (build 0)");
  EXPECT_EQ(reply_text(ask(s, "Fly"), 0), "Parse Error");
  EXPECT_EQ(reply_text(ask(s, "GetParameters 3D")), "Parameters not available");
}

TEST(QtmServerSession, ParametersFollowTheNegotiatedFormat) {
  ServerSession s({});
  const std::vector<std::string> names = {"Body1", "Body2"};
  (void)ask(s, "Version 1.19");
  auto old_xml = parse_parameters(reply_text(ask(s, "GetParameters 6D", names), 2));
  ASSERT_TRUE(old_xml);
  EXPECT_EQ(old_xml.value().declared_bodies, 2u);
  EXPECT_EQ(old_xml.value().root, "QTM_Parameters_Ver_1.19");
  (void)ask(s, "Version 1.25");
  auto new_xml = parse_parameters(reply_text(ask(s, "GetParameters All", names), 2));
  ASSERT_TRUE(new_xml);
  EXPECT_FALSE(new_xml.value().declared_bodies);
  EXPECT_EQ(new_xml.value().bodies.size(), 2u);
  EXPECT_TRUE(new_xml.value().frequency_hz);
}

TEST(QtmServerSession, StreamFramesRatesUdpComponentsAndStop) {
  ServerSession s({.frequency_hz = 100.0});
  ServedFrame frame;
  frame.names = {"A"};
  frame.bodies = {Body6d{}};
  EXPECT_EQ(reply_text(ask(s, "StreamFrames AllFrames 6D"), 0),
            "mocaplink's emulator serves data from protocol 1.8 on");
  (void)ask(s, "Version 1.19");
  EXPECT_TRUE(ask(s, "StreamFrames Frequency:50 UDP:127.0.0.1:5000 6DRes 6DEuler", {}, &frame)
                  .empty());  // no reply
  ASSERT_TRUE(s.streaming());
  ASSERT_TRUE(s.udp());
  EXPECT_EQ(s.udp()->address, "127.0.0.1");
  EXPECT_EQ(s.udp()->port, 5000);
  int sent = 0;
  for (int i = 0; i < 10; ++i) sent += s.on_new_frame(frame).has_value() ? 1 : 0;
  EXPECT_EQ(sent, 5);  // 100 Hz / 50 Hz
  EXPECT_TRUE(ask(s, "StreamFrames FrequencyDivisor:1 UDP:6000 All", {}, &frame).empty());
  const auto all = s.on_new_frame(frame);
  ASSERT_TRUE(all);
  const auto data = parse_data(std::span(*all).subspan(8));
  ASSERT_TRUE(data);
  EXPECT_EQ(data.value().six_dof.size(), 4u);
  EXPECT_EQ(s.udp()->address, "");
  EXPECT_EQ(reply_text(ask(s, "StreamFrames AllFrames UDP:80 6D"), 0),
            "UDP port must be 1023 to 65535");
  EXPECT_EQ(reply_text(ask(s, "StreamFrames AllFrames 3D"), 0), "Component 3D not available");
  EXPECT_EQ(reply_text(ask(s, "StreamFrames Sometimes 6D"), 0), "Parse Error");
  EXPECT_TRUE(ask(s, "StreamFrames Stop").empty());
  EXPECT_FALSE(s.streaming());
  EXPECT_FALSE(s.on_new_frame(frame));
  ServerSession only_6d({.components = {Component::six_d}});
  (void)ask(only_6d, "Version 1.19");
  EXPECT_EQ(reply_text(ask(only_6d, "StreamFrames AllFrames 6DRes"), 0),
            "Component 6DRes not available");
  // Before any frame: "No More Data" (§3.3).
  const auto none = ask(only_6d, "StreamFrames AllFrames 6D");
  ASSERT_EQ(none.size(), 1u);
  EXPECT_EQ(parse_packet(none[0], kDefaultMaxPacketBytes).value().type, 4u);
}

}  // namespace
}  // namespace mocaplink::wire::qtm
