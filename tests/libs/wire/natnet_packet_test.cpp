// NatNet codecs against independent references: the worked hex examples of natnet.md §9 (parse
// AND encode byte for byte), the real Motive 2.1 / NatNet 3.0 captures of mje-nz/python_natnet
// (tests/data/natnet/python_natnet, BSD-3) compared field by field with what the official NatNet
// SampleClient printed for the same session (SampleClient_output.txt; every frame of
// traffic.pcapng it printed), and the Motive 1.5/1.7/1.9 frames (NatNet 2.5/2.7/2.9) of
// nordmoen/natnet-decode (MIT) for the 2.x path.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <numbers>
#include <regex>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "mocaplink/wire/natnet_mocap_frame.hpp"
#include "mocaplink/wire/natnet_packet.hpp"
#include "vicon_test_bytes.hpp"

namespace nn = mocaplink::wire::natnet;
using mocaplink::wire::vicon::test::hex;

namespace {

const std::string kCaptures = "tests/data/natnet/python_natnet/";
const std::string kCaptures2x = "tests/data/natnet/natnet_decode/";

std::vector<std::byte> read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  EXPECT_TRUE(in.good()) << path;
  std::vector<char> raw((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<std::byte> out(raw.size());
  for (std::size_t i = 0; i < raw.size(); ++i) out[i] = static_cast<std::byte>(raw[i]);
  return out;
}

nn::Packet split(const std::vector<std::byte>& datagram, nn::MessageId id) {
  auto p = nn::split_packet(datagram);
  EXPECT_TRUE(p.ok());
  EXPECT_EQ(p.value().id, static_cast<std::uint16_t>(id));
  EXPECT_EQ(p.value().trailing_bytes, 0u);
  return p.value();
}

// The SampleClient prints with "%3.2f" using the Windows C runtime, which first converts the value
// to 17 significant digits and then rounds that decimal half away from zero (1356.175, stored as
// 1356.17499999999995…, prints "1356.18"; glibc prints "1356.17"). Do the same here.
std::string f2(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.16e", std::abs(v));  // d.dddddddddddddddde±XX
  const std::string text(buf);
  const std::size_t e = text.find('e');
  const int exponent = std::stoi(text.substr(e + 1));
  std::string digits = text.substr(0, 1) + text.substr(2, e - 2);  // 17 digits, point after 1st
  // Place the decimal point: integer part has exponent + 1 digits.
  int int_digits = exponent + 1;
  if (int_digits <= 0) {
    digits.insert(0, static_cast<std::size_t>(1 - int_digits), '0');
    int_digits = 1;
  }
  digits.append(4, '0');
  std::string kept = digits.substr(0, static_cast<std::size_t>(int_digits) + 2);
  if (digits[static_cast<std::size_t>(int_digits) + 2] >= '5') {
    for (std::size_t i = kept.size(); i-- > 0;) {
      if (kept[i] != '9') {
        ++kept[i];
        break;
      }
      kept[i] = '0';
      if (i == 0) kept.insert(kept.begin(), '1');
    }
  }
  std::string out = kept.substr(0, kept.size() - 2) + "." + kept.substr(kept.size() - 2);
  if (std::signbit(v)) out = "-" + out;  // the CRT prints "-0.00" for small negatives too
  return out;
}

constexpr std::string_view kFrame30 =
    "070074006400000000000000000000000100000007000000cdcccc3dcdcc4c3e9a99993e00000000000000000000"
    "00000000803f6f12033a0100000000000000000000000000000000000000000000000000000000000000294040420f"
    "0000000000c0800f000000000090880f0000000000000000000000";
constexpr std::string_view kFrame41 =
    "0700a0006400000000000000000000000000000000000000010000002600000007000000cdcccc3dcdcc4c3e9a9999"
    "3e0000000000000000000000000000803f6f12033a0100000000000000000000000000000000000000000000000000"
    "0"
    "00000000000000000000000000000000000000000000000000000000000294040420f0000000000c0800f000000000"
    "0"
    "90880f00000000000000000000000000000000000000";
constexpr std::string_view kModel30 =
    "05002700010000000100000044726f6e65310007000000ffffffff00000000000000000000000000000000";
constexpr std::string_view kModel42 =
    "05003b0001000000010000002f00000044726f6e65310007000000ffffffff00000000000000000000000000000000"
    "00000000000000000000803f00000000";

// The frame of §9 (both versions).
nn::FrameOfData golden_frame() {
  nn::FrameOfData f;
  f.frame_number = 100;
  nn::RigidBodySample rb;
  rb.id = 7;
  rb.position = {0.1f, 0.2f, 0.3f};
  rb.orientation = {0.0f, 0.0f, 0.0f, 1.0f};
  rb.mean_error = 0.0005f;
  rb.params = 1;
  f.rigid_bodies.push_back(rb);
  f.timestamp_s = 12.5;
  f.mid_exposure_ticks = 1'000'000;
  f.data_received_ticks = 1'016'000;
  f.transmit_ticks = 1'018'000;
  return f;
}

void expect_golden_frame(const nn::FrameOfData& f) {
  EXPECT_EQ(f.frame_number, 100);
  ASSERT_EQ(f.rigid_bodies.size(), 1u);
  const auto& rb = f.rigid_bodies[0];
  EXPECT_EQ(rb.id, 7);
  EXPECT_FLOAT_EQ(rb.position[0], 0.1f);
  EXPECT_FLOAT_EQ(rb.position[1], 0.2f);
  EXPECT_FLOAT_EQ(rb.position[2], 0.3f);
  EXPECT_FLOAT_EQ(rb.orientation[3], 1.0f);
  EXPECT_FLOAT_EQ(rb.mean_error, 0.0005f);
  EXPECT_TRUE(rb.tracking_valid());
  EXPECT_EQ(f.timestamp_s, 12.5);
  EXPECT_EQ(f.mid_exposure_ticks, 1'000'000u);
  EXPECT_EQ(f.data_received_ticks, 1'016'000u);
  EXPECT_EQ(f.transmit_ticks, 1'018'000u);
}

TEST(NatnetGolden, Frame30ParsesAndEncodesExactly) {
  const auto bytes = hex(kFrame30);
  ASSERT_EQ(bytes.size(), 120u);
  auto f = nn::parse_frame(split(bytes, nn::MessageId::frame_of_data).payload, {3, 0});
  ASSERT_TRUE(f.ok()) << f.error().reason;
  expect_golden_frame(f.value());
  EXPECT_EQ(nn::encode_frame(golden_frame(), {3, 0}), bytes);
}

TEST(NatnetGolden, Frame41ParsesAndEncodesExactly) {
  const auto bytes = hex(kFrame41);
  ASSERT_EQ(bytes.size(), 164u);
  auto f = nn::parse_frame(split(bytes, nn::MessageId::frame_of_data).payload, {4, 1});
  ASSERT_TRUE(f.ok()) << f.error().reason;
  expect_golden_frame(f.value());
  EXPECT_EQ(nn::encode_frame(golden_frame(), {4, 1}), bytes);
  // Every version of the 4.x family our emulator serves round-trips through the parser.
  for (const nn::Version v : {nn::Version{3, 1}, nn::Version{4, 0}, nn::Version{4, 2}}) {
    auto again = nn::parse_frame(
        split(nn::encode_frame(golden_frame(), v), nn::MessageId::frame_of_data).payload, v);
    ASSERT_TRUE(again.ok()) << v.to_string();
  }
}

TEST(NatnetGolden, ModelDefinitionsParseAndEncodeExactly) {
  for (const auto& [text, version] :
       {std::pair{kModel30, nn::Version{3, 0}}, std::pair{kModel42, nn::Version{4, 2}}}) {
    const auto bytes = hex(text);
    auto defs =
        nn::parse_model_definitions(split(bytes, nn::MessageId::model_def).payload, version);
    ASSERT_TRUE(defs.ok()) << defs.error().reason;
    ASSERT_EQ(defs.value().rigid_bodies.size(), 1u);
    const auto& rb = defs.value().rigid_bodies[0];
    EXPECT_EQ(rb.name, "Drone1");
    EXPECT_EQ(rb.id, 7);
    EXPECT_EQ(rb.parent_id, -1);
    EXPECT_EQ(defs.value().size_mismatches, 0u);
    nn::ModelDefinitions mine;
    nn::RigidBodyDescription d;
    d.name = "Drone1";
    d.id = 7;
    mine.rigid_bodies.push_back(d);
    EXPECT_EQ(nn::encode_model_definitions(mine, version), bytes) << version.to_string();
  }
}

TEST(NatnetCapture, ServerInfoConnectAndEcho) {
  const auto info_bytes = read_file(kCaptures + "serverinfo_packet_v3.bin");
  auto info = nn::parse_server_info(split(info_bytes, nn::MessageId::server_info).payload);
  ASSERT_TRUE(info.ok()) << info.error().reason;
  const nn::ServerInfo& i = info.value();
  // SampleClient: "Application: Motive (ver. 2.1.0.0)", "NatNet Version: 3.0.0.0".
  EXPECT_EQ(i.sender.name, "Motive");
  EXPECT_EQ(i.sender.app_version, (std::array<std::uint8_t, 4>{2, 1, 0, 0}));
  EXPECT_EQ(i.sender.natnet_version, (std::array<std::uint8_t, 4>{3, 0, 0, 0}));
  EXPECT_TRUE(i.has_connection_info);
  EXPECT_EQ(i.clock_hz, 3'312'787u);
  EXPECT_EQ(i.data_port, 1511);
  EXPECT_TRUE(i.multicast);
  EXPECT_EQ(i.multicast_group, (std::array<std::uint8_t, 4>{239, 255, 42, 99}));
  // Our encoder writes Motive's bytes after the name block (Motive leaves stack bytes after the
  // name's NUL; we write zeros).
  const auto mine = nn::encode_server_info(i);
  ASSERT_EQ(mine.size(), info_bytes.size());
  EXPECT_TRUE(std::equal(mine.begin() + 4 + 256, mine.end(), info_bytes.begin() + 4 + 256));

  for (const char* name : {"connect_packet_v3.bin", "discovery_packet_v3.bin"}) {
    const auto bytes = read_file(kCaptures + name);
    auto p = nn::split_packet(bytes);
    ASSERT_TRUE(p.ok());
    auto c = nn::parse_connect(p.value().payload);
    ASSERT_TRUE(c.ok()) << c.error().reason;
    EXPECT_EQ(c.value().sender.name, "NatNetLib");
    EXPECT_EQ(c.value().sender.natnet_version, (std::array<std::uint8_t, 4>{3, 0, 0, 0}));
  }
  const auto request = read_file(kCaptures + "requestmodeldef_packet_v3.bin");
  EXPECT_EQ(nn::encode_empty(nn::MessageId::request_model_def), request);
  const auto echo = read_file(kCaptures + "echorequest_packet_v3.bin");
  EXPECT_TRUE(nn::parse_echo_request(split(echo, nn::MessageId::echo_request).payload).ok());
}

TEST(NatnetCapture, ModelDefinitionsMatchSampleClient) {
  const auto bytes = read_file(kCaptures + "modeldef_packet_v3.bin");
  auto defs = nn::parse_model_definitions(split(bytes, nn::MessageId::model_def).payload, {3, 0});
  ASSERT_TRUE(defs.ok()) << defs.error().reason;
  const nn::ModelDefinitions& d = defs.value();
  // "Received 3 Data Descriptions": rigid body RaceQuad (ID 2, parent -1, offset 0,0,0, five
  // markers), marker sets "RaceQuad" (Marker1..5) and "all" (RaceQuad_1..5).
  ASSERT_EQ(d.rigid_bodies.size(), 1u);
  const auto& rb = d.rigid_bodies[0];
  EXPECT_EQ(rb.name, "RaceQuad");
  EXPECT_EQ(rb.id, 2);
  EXPECT_EQ(rb.parent_id, -1);
  EXPECT_EQ(f2(rb.offset[0]) + "," + f2(rb.offset[1]) + "," + f2(rb.offset[2]), "0.00,0.00,0.00");
  const std::vector<std::string> printed = {"0.16, 0.04, -0.03", "-0.03, 0.04, -0.02",
                                            "0.19, -0.03, 0.15", "-0.07, 0.00, 0.03",
                                            "-0.06, -0.03, -0.14"};
  ASSERT_EQ(rb.marker_positions.size(), printed.size());
  for (std::size_t k = 0; k < printed.size(); ++k) {
    const auto& p = rb.marker_positions[k];
    EXPECT_EQ(f2(p[0]) + ", " + f2(p[1]) + ", " + f2(p[2]), printed[k]) << "marker " << k;
  }
  ASSERT_EQ(d.marker_sets.size(), 2u);
  EXPECT_EQ(d.marker_sets[0].name, "RaceQuad");
  EXPECT_EQ(d.marker_sets[0].marker_names,
            (std::vector<std::string>{"Marker1", "Marker2", "Marker3", "Marker4", "Marker5"}));
  EXPECT_EQ(d.marker_sets[1].name, "all");
  EXPECT_EQ(d.marker_sets[1].marker_names.size(), 5u);
  EXPECT_EQ(d.marker_sets[1].marker_names[0], "RaceQuad_1");
  const nn::BodyTable table = nn::body_table(d);
  EXPECT_EQ(table.names.at(2), "RaceQuad");
}

// One frame as the SampleClient printed it.
struct PrintedFrame {
  std::string timestamp, system_latency_ms;
  std::vector<std::string> other_markers;  // "x\ty\tz"
  std::vector<std::string> rigid_bodies;   // "[ID=..  Error=..  Valid=..]|x\ty\tz\tqx\tqy\tqz\tqw"
  std::vector<std::string> labeled;        // the bracketed part of each line
};

std::map<std::int32_t, PrintedFrame> printed_frames() {
  std::ifstream in(kCaptures + "SampleClient_output.txt");
  std::map<std::int32_t, PrintedFrame> out;
  PrintedFrame* cur = nullptr;
  std::string line;
  const std::regex id_re("^FrameID : (\\d+)");
  const std::regex ts_re("^Timestamp : (.*)");
  const std::regex sys_re("^System latency : ([0-9.]+) milliseconds");
  const std::regex other_re("^Other Marker \\d+ : (.*)");
  const std::regex rb_re("^Rigid Body (\\[.*\\])");
  const std::regex pose_re("^\t(-?[0-9].*)");
  const std::regex lm_re("^Labeled Marker (\\[.*)");
  std::smatch m;
  while (std::getline(in, line)) {
    if (std::regex_search(line, m, id_re)) {
      cur = &out[std::stoi(m[1])];
    } else if (cur == nullptr) {
      continue;
    } else if (std::regex_search(line, m, ts_re)) {
      cur->timestamp = m[1];
    } else if (std::regex_search(line, m, sys_re)) {
      cur->system_latency_ms = m[1];
    } else if (std::regex_search(line, m, other_re)) {
      cur->other_markers.push_back(m[1]);
    } else if (std::regex_search(line, m, rb_re)) {
      cur->rigid_bodies.push_back(std::string(m[1]) + "|");
    } else if (std::regex_search(line, m, pose_re) && !cur->rigid_bodies.empty()) {
      cur->rigid_bodies.back() += m[1];
    } else if (std::regex_search(line, m, lm_re)) {
      cur->labeled.push_back(m[1]);
    }
  }
  return out;
}

// The SampleClient's own formatting of the decoded frame (NatNet 3.0 SampleClient.cpp prints
// these fields with "%3.2f"; labelled-marker ids split into model id (high 16) and marker id).
PrintedFrame print_like_sample_client(const nn::FrameOfData& f, std::uint64_t clock_hz) {
  PrintedFrame p;
  p.timestamp = f2(f.timestamp_s);
  p.system_latency_ms = f2(static_cast<double>(f.transmit_ticks - f.mid_exposure_ticks) * 1000.0 /
                           static_cast<double>(clock_hz));
  for (const auto& m : f.other_markers) {
    p.other_markers.push_back(f2(m[0]) + "\t" + f2(m[1]) + "\t" + f2(m[2]));
  }
  for (const auto& rb : f.rigid_bodies) {
    std::string s = "[ID=" + std::to_string(rb.id) + "  Error=" + f2(rb.mean_error) +
                    "  Valid=" + std::to_string(rb.tracking_valid() ? 1 : 0) + "]|";
    s += f2(rb.position[0]) + "\t" + f2(rb.position[1]) + "\t" + f2(rb.position[2]) + "\t" +
         f2(rb.orientation[0]) + "\t" + f2(rb.orientation[1]) + "\t" + f2(rb.orientation[2]) +
         "\t" + f2(rb.orientation[3]);
    p.rigid_bodies.push_back(s);
  }
  for (const auto& m : f.labeled_markers) {
    const auto id = static_cast<std::uint32_t>(m.id);
    p.labeled.push_back("[ModelID=" + std::to_string(id >> 16) +
                        ", MarkerID=" + std::to_string(id & 0xFFFFu) +
                        ", Occluded=" + std::to_string((m.params & 0x01) != 0 ? 1 : 0) +
                        ", PCSolved=" + std::to_string((m.params & 0x02) != 0 ? 1 : 0) +
                        ", ModelSolved=" + std::to_string((m.params & 0x04) != 0 ? 1 : 0) +
                        "] [size=" + f2(m.size) + "] [pos=" + f2(m.position[0]) + "," +
                        f2(m.position[1]) + "," + f2(m.position[2]) + "]");
  }
  return p;
}

void expect_printed(const PrintedFrame& mine, const PrintedFrame& theirs, std::int32_t id) {
  EXPECT_EQ(mine.timestamp, theirs.timestamp) << "frame " << id;
  EXPECT_EQ(mine.system_latency_ms, theirs.system_latency_ms) << "frame " << id;
  EXPECT_EQ(mine.other_markers, theirs.other_markers) << "frame " << id;
  EXPECT_EQ(mine.rigid_bodies, theirs.rigid_bodies) << "frame " << id;
  EXPECT_EQ(mine.labeled, theirs.labeled) << "frame " << id;
}

TEST(NatnetCapture, FrameMatchesSampleClient) {
  const auto printed = printed_frames();
  ASSERT_EQ(printed.size(), 251u);
  const auto bytes = read_file(kCaptures + "mocapframe_packet_v3.bin");
  auto f = nn::parse_frame(split(bytes, nn::MessageId::frame_of_data).payload, {3, 0});
  ASSERT_TRUE(f.ok()) << f.error().reason;
  ASSERT_EQ(f.value().frame_number, 162734);
  ASSERT_TRUE(printed.count(162734));
  expect_printed(print_like_sample_client(f.value(), 3'312'787), printed.at(162734), 162734);
  EXPECT_EQ(f.value().mid_exposure_ticks, 1'416'497'730'518u);
  EXPECT_EQ(f.value().transmit_ticks, 1'416'497'748'722u);

  // Through the body table: RaceQuad tracked at the printed pose, Motive's latency 5.5 ms.
  nn::ModelDefinitions defs;
  nn::RigidBodyDescription rb;
  rb.name = "RaceQuad";
  rb.id = 2;
  defs.rigid_bodies.push_back(rb);
  const nn::MappedFrame mapped = nn::to_mocap_frame(f.value(), nn::body_table(defs), 3'312'787);
  ASSERT_EQ(mapped.frame.bodies.size(), 1u);
  EXPECT_EQ(mapped.frame.bodies[0].name, "RaceQuad");
  EXPECT_TRUE(mapped.frame.bodies[0].tracked);
  EXPECT_EQ(f2(mapped.frame.bodies[0].p_world_m.y()), "1.45");
  ASSERT_TRUE(mapped.frame.source_latency);
  EXPECT_NEAR(static_cast<double>(mapped.frame.source_latency->count()) / 1e6, 5.495, 0.01);
  EXPECT_EQ(mapped.frame.frame_number, 162734u);

  const auto occluded = read_file(kCaptures + "mocapframe_packet_occluded_v3.bin");
  auto o = nn::parse_frame(split(occluded, nn::MessageId::frame_of_data).payload, {3, 0});
  ASSERT_TRUE(o.ok()) << o.error().reason;
  ASSERT_EQ(o.value().marker_sets.size(), 2u);
  EXPECT_EQ(o.value().marker_sets[0].name, "FakeTree");
  EXPECT_EQ(o.value().marker_sets[1].name, "all");
  ASSERT_EQ(o.value().rigid_bodies.size(), 1u);
  EXPECT_EQ(o.value().rigid_bodies[0].id, 7);
  EXPECT_TRUE(o.value().rigid_bodies[0].tracking_valid());
  EXPECT_EQ(o.value().labeled_markers.size(), 4u);
}

// UDP payloads sent to `port` in a pcapng file (Ethernet, IPv4, unfragmented). Written from the
// pcapng and IPv4/UDP specifications for this test only.
std::vector<std::vector<std::byte>> udp_payloads(const std::vector<std::byte>& file,
                                                 std::uint16_t port) {
  auto u32 = [&](std::size_t at) {
    return static_cast<std::uint32_t>(file[at]) | static_cast<std::uint32_t>(file[at + 1]) << 8 |
           static_cast<std::uint32_t>(file[at + 2]) << 16 |
           static_cast<std::uint32_t>(file[at + 3]) << 24;
  };
  auto be16 = [&](std::size_t at) {
    return static_cast<std::uint16_t>(static_cast<unsigned>(file[at]) << 8 |
                                      static_cast<unsigned>(file[at + 1]));
  };
  std::vector<std::vector<std::byte>> out;
  std::size_t at = 0;
  while (at + 12 <= file.size()) {
    const std::uint32_t type = u32(at);
    const std::uint32_t length = u32(at + 4);
    if (length < 12 || at + length > file.size()) break;
    if (type == 6) {  // enhanced packet block
      const std::size_t data = at + 28;
      const std::uint32_t captured = u32(at + 20);
      const std::size_t ip = data + 14;
      if (be16(data + 12) == 0x0800 && (static_cast<unsigned>(file[ip + 9]) == 17)) {
        const std::size_t ihl = (static_cast<unsigned>(file[ip]) & 0x0Fu) * 4u;
        const bool fragment = (be16(ip + 6) & 0x3FFFu) != 0;
        const std::size_t udp = ip + ihl;
        if (!fragment && be16(udp + 2) == port) {
          const std::size_t len = be16(udp + 4) - 8u;
          if (udp + 8 + len <= data + captured) {
            out.emplace_back(file.begin() + static_cast<std::ptrdiff_t>(udp + 8),
                             file.begin() + static_cast<std::ptrdiff_t>(udp + 8 + len));
          }
        }
      }
    }
    at += length;
  }
  return out;
}

TEST(NatnetCapture, EveryPrintedFrameOfTheTrafficCaptureMatches) {
  const auto printed = printed_frames();
  const auto datagrams = udp_payloads(read_file(kCaptures + "traffic.pcapng"), 1511);
  ASSERT_GE(datagrams.size(), 500u);
  std::size_t compared = 0;
  for (const auto& d : datagrams) {
    auto p = nn::split_packet(d);
    ASSERT_TRUE(p.ok());
    if (p.value().id != static_cast<std::uint16_t>(nn::MessageId::frame_of_data)) continue;
    auto f = nn::parse_frame(p.value().payload, {3, 0});
    ASSERT_TRUE(f.ok()) << f.error().reason << " at " << f.error().offset;
    const auto it = printed.find(f.value().frame_number);
    if (it == printed.end()) continue;
    expect_printed(print_like_sample_client(f.value(), 3'312'787), it->second,
                   f.value().frame_number);
    ++compared;
  }
  EXPECT_EQ(compared, printed.size());  // every frame the SampleClient printed is in the capture
}

TEST(NatnetCapture, Natnet2xFramesDecodeExactly) {
  // natnet-decode's own tests: marker sets ("all" and one body's), 2 other markers (none with
  // Motive 1.9), one rigid body, no skeleton, 3 labelled markers; the -000 file is the server's
  // 264-byte server info (pre-3.0) naming its NatNet version.
  for (const auto& [motive, version, others] :
       {std::tuple{"1.5.0", nn::Version{2, 5}, 2u}, std::tuple{"1.7.2", nn::Version{2, 7}, 2u},
        std::tuple{"1.9.0", nn::Version{2, 9}, 0u}}) {
    for (const char* n : {"001", "002"}) {
      const std::string file = kCaptures2x + "frame-motive-" + motive + "-" + n + ".bin";
      const auto bytes = read_file(file);
      auto f = nn::parse_frame(split(bytes, nn::MessageId::frame_of_data).payload, version);
      ASSERT_TRUE(f.ok()) << file << ": " << f.error().reason << " at " << f.error().offset;
      ASSERT_EQ(f.value().marker_sets.size(), 2u) << file;
      EXPECT_EQ(f.value().other_markers.size(), others) << file;
      ASSERT_EQ(f.value().rigid_bodies.size(), 1u) << file;
      EXPECT_EQ(f.value().skeletons, 0u) << file;
      EXPECT_EQ(f.value().labeled_markers.size(), 3u) << file;
    }
    const auto ping_bytes = read_file(kCaptures2x + "frame-motive-" + motive + "-000.bin");
    auto ping = nn::split_packet(ping_bytes);
    ASSERT_TRUE(ping.ok());
    EXPECT_EQ(ping.value().id, static_cast<std::uint16_t>(nn::MessageId::server_info));
    auto c = nn::parse_server_info(ping.value().payload);
    ASSERT_TRUE(c.ok()) << c.error().reason;
    EXPECT_EQ(c.value().sender.name, "NatNetLib");
    EXPECT_FALSE(c.value().has_connection_info);
    EXPECT_EQ(c.value().version(), version);
  }
}

TEST(NatnetCodec, RejectsTruncatedAndTrailingBytes) {
  auto bytes = hex(kFrame30);
  auto payload = split(bytes, nn::MessageId::frame_of_data).payload;
  for (std::size_t n = 0; n < payload.size(); ++n) {
    EXPECT_FALSE(nn::parse_frame(payload.first(n), {3, 0}).ok()) << n;
  }
  bytes.push_back(std::byte{0});
  auto longer = nn::split_packet(bytes);
  ASSERT_TRUE(longer.ok());
  EXPECT_EQ(longer.value().trailing_bytes, 1u);
  // The same bytes read as 4.1 do not end where they should.
  EXPECT_FALSE(nn::parse_frame(payload, {4, 1}).ok());
  // A datagram shorter than its header says.
  EXPECT_FALSE(nn::split_packet(std::vector<std::byte>(bytes.begin(), bytes.begin() + 50)).ok());
  // A rigid-body count larger than the payload allows.
  auto lying = hex(kFrame30);
  lying[4 + 12] = std::byte{0xff};  // rigid-body count (after frame number and two counts)
  EXPECT_FALSE(nn::parse_frame(split(lying, nn::MessageId::frame_of_data).payload, {3, 0}).ok());
  EXPECT_FALSE(nn::parse_frame(payload, {5, 0}).ok());
}

TEST(NatnetCodec, AResponseTextIsReadWithOrWithoutItsNul) {
  // "Bitstream,4.1.0": 4-byte header (id 3, 15 bytes), the text, no NUL.
  const auto bare = nn::encode_response_text("Bitstream,4.1.0");
  ASSERT_EQ(bare.size(), 4u + 15u);
  EXPECT_EQ(bare[0], std::byte{3});
  EXPECT_EQ(bare[2], std::byte{15});
  EXPECT_NE(bare.back(), std::byte{0});
  const auto packet = nn::split_packet(bare);
  ASSERT_TRUE(packet.ok());
  EXPECT_EQ(nn::parse_response_text(packet.value().payload), "Bitstream,4.1.0");
  // A server that terminates it, and one that pads after the NUL, read the same.
  const auto terminated = nn::encode_string_packet(nn::MessageId::response, "Bitstream,4.1.0");
  EXPECT_EQ(nn::parse_response_text(nn::split_packet(terminated).value().payload),
            "Bitstream,4.1.0");
  std::vector<std::byte> padded(terminated.begin() + 4, terminated.end());
  padded.insert(padded.end(), {std::byte{'x'}, std::byte{0}});
  EXPECT_EQ(nn::parse_response_text(padded), "Bitstream,4.1.0");
  EXPECT_EQ(nn::parse_response_text({}), "");
}

TEST(NatnetMapping, TrackingValidBitAndBadPosesAreUntracked) {
  nn::FrameOfData f = golden_frame();
  nn::RigidBodySample lost = f.rigid_bodies[0];
  lost.id = 8;
  lost.params = 0;
  nn::RigidBodySample bad = f.rigid_bodies[0];
  bad.id = 9;
  bad.orientation = {0.0f, 0.0f, 0.0f, 0.5f};
  nn::RigidBodySample unknown = f.rigid_bodies[0];
  unknown.id = 10;
  f.rigid_bodies.push_back(lost);
  f.rigid_bodies.push_back(bad);
  f.rigid_bodies.push_back(unknown);
  nn::BodyTable table;
  table.names = {{7, "Drone1"}, {8, "Lost"}, {9, "Bad"}};
  const nn::MappedFrame m = nn::to_mocap_frame(f, table, 1'000'000);
  ASSERT_EQ(m.frame.bodies.size(), 3u);
  EXPECT_TRUE(m.frame.bodies[0].tracked);
  EXPECT_FALSE(m.frame.bodies[1].tracked);
  EXPECT_FALSE(m.frame.bodies[2].tracked);
  EXPECT_EQ(m.invalid_poses, 1u);
  EXPECT_EQ(m.unknown_ids, 1u);
  // 1 000 000 ticks at 1 MHz = 1 s; Motive's latency (1 018 000 − 1 000 000) ticks = 18 ms.
  EXPECT_EQ(m.frame.capture_time.time_since_epoch().count(), 1'000'000'000);
  EXPECT_EQ(m.frame.source_latency->count(), 18'000'000);
  // Two ids with one name: neither is used.
  nn::ModelDefinitions defs;
  nn::RigidBodyDescription a;
  a.name = "Twin";
  a.id = 1;
  defs.rigid_bodies = {a, a};
  defs.rigid_bodies[1].id = 2;
  EXPECT_TRUE(nn::body_table(defs).names.empty());
  EXPECT_EQ(nn::body_table(defs).ambiguous.count("Twin"), 1u);
}

TEST(NatnetMapping, ZUpToMotiveYUp) {
  // Independent of our code: the Y-up frame has y' = up = z, z' = x' × y' = x × z = −y.
  EXPECT_TRUE(nn::z_up_to_y_up(Eigen::Vector3d(1, 2, 3)).isApprox(Eigen::Vector3d(1, 3, -2)));
  // A yaw of 90° about z-up is a rotation of 90° about Motive's +y.
  const Eigen::Quaterniond yaw(Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitZ()));
  const Eigen::Quaterniond expected(
      Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitY()));
  EXPECT_TRUE(nn::z_up_to_y_up(yaw).isApprox(expected, 1e-12));
}

TEST(NatnetMapping, ServedModelsFlagTheChange) {
  nn::ServedModels models;
  mocaplink::core::MocapFrame f;
  f.bodies.resize(2);
  f.bodies[0].name = "Body1";
  f.bodies[1].name = "Body2";
  EXPECT_EQ(models.frame_of(f, true, 1'000'000).params & nn::kParamModelsChanged, 0);
  EXPECT_EQ(models.frame_of(f, true, 1'000'000).params & nn::kParamModelsChanged, 0);
  f.bodies.pop_back();
  const auto changed = models.frame_of(f, true, 1'000'000);
  EXPECT_NE(changed.params & nn::kParamModelsChanged, 0);
  EXPECT_FALSE(changed.rigid_bodies[0].tracking_valid());  // untracked bodies are served invalid
  ASSERT_EQ(models.definitions().rigid_bodies.size(), 1u);
  f.bodies.resize(2);
  f.bodies[1].name = "Body2";
  const auto back = models.frame_of(f, true, 1'000'000);
  EXPECT_EQ(back.rigid_bodies[1].id, 2);  // ids stay with their names
}

// A client that asked for the models before the first frame was told of an empty list: the first
// frame flags the change, so the client asks again (a client that asked nothing is not prompted).
TEST(NatnetMapping, TheFirstFrameFlagsTheChangeOnlyAfterAnEmptyListWasDescribed) {
  mocaplink::core::MocapFrame f;
  f.bodies.resize(1);
  f.bodies[0].name = "Body1";
  nn::ServedModels asked;
  EXPECT_TRUE(asked.definitions().rigid_bodies.empty());
  EXPECT_NE(asked.frame_of(f, true, 1'000'000).params & nn::kParamModelsChanged, 0);
  EXPECT_EQ(asked.frame_of(f, true, 1'000'000).params & nn::kParamModelsChanged, 0);
  ASSERT_EQ(asked.definitions().rigid_bodies.size(), 1u);
  EXPECT_EQ(asked.definitions().rigid_bodies[0].name, "Body1");

  nn::ServedModels empty_frames;  // a frame without bodies is no change from the empty list
  (void)empty_frames.definitions();
  EXPECT_EQ(empty_frames.frame_of({}, true, 1'000'000).params & nn::kParamModelsChanged, 0);
}

}  // namespace
