// Replay regression (issue 3 "Evidence"; STYLE.md "change indication"): a committed recording
// (data/replay/two_bodies.csv, DESIGN.md CSV format, from sim:// with two bodies and occlusions) is
// run through the Bridge with two vehicles — "quad" (px4, Body2, 50 Hz) and "rover"
// (ardupilot-gps, Body1, 10 Hz) — with injected host time, scripted vehicle replies and 100 ms
// ticks. Every message sent and every event is written as one text line; the result must match
// data/replay/two_bodies.expected.txt. A behaviour change shows up as a diff of that file.
//
// The test never writes into the source tree. On mismatch the actual output is written to
// two_bodies.actual.txt in $MOCAPLINK_REPLAY_OUT, or else in this test's build directory
// (build/<preset>/tests/libs/core/); to accept an intended change, review the diff and copy it
// over the expected file (the failure message prints the exact `cp` command):
//   build/<preset>/tests/libs/core/two_bodies.actual.txt
//   → tests/libs/core/data/replay/two_bodies.expected.txt
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include <gtest/gtest.h>

#include "mocaplink/core/bridge.hpp"
#include "mocaplink/wire/recording_csv.hpp"

namespace mocaplink::core {
namespace {

using std::chrono::milliseconds;

const std::string kDir = MOCAPLINK_REPLAY_DIR;

/// Where a failing run leaves its output: $MOCAPLINK_REPLAY_OUT, else the build directory.
std::string output_dir() {
  const char* dir = std::getenv("MOCAPLINK_REPLAY_OUT");
  return dir != nullptr && *dir != '\0' ? std::string(dir) : std::string(MOCAPLINK_REPLAY_OUT_DIR);
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string fixed6(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6f", v);
  return buf;
}

template <typename T>
std::string value_text(const T& v) {
  if constexpr (std::is_floating_point_v<T>) {
    return fixed6(static_cast<double>(v));
  } else {
    return std::to_string(+v);  // + promotes (u)int8 to print as a number
  }
}

/// Array fields: covariances by their diagonal (21 → 0, 6, 11, 15, 18, 20; 9 → 0, 4, 8), others
/// in full; elements joined with '|'.
template <typename T, std::size_t N>
std::string value_text(const std::array<T, N>& a) {
  std::vector<std::size_t> idx;
  if constexpr (N == 21) {
    idx = {0, 6, 11, 15, 18, 20};
  } else if constexpr (N == 9) {
    idx = {0, 4, 8};
  } else {
    for (std::size_t i = 0; i < N; ++i) idx.push_back(i);
  }
  std::string out;
  for (std::size_t i : idx) out += (out.empty() ? "" : "|") + value_text(a[i]);
  return out;
}

double seconds_since(HostTime start, HostTime t) {
  return to_seconds(t - start);
}

std::string message_line(HostTime start, const OutgoingMessage& o) {
  std::string line = fixed6(seconds_since(start, o.time)) + "," + std::to_string(o.vehicle) + "," +
                     std::to_string(o.frame.bytes()[4]);
  std::visit(
      [&](const auto& m) {
        line += ",";
        line += std::remove_cvref_t<decltype(m)>::kName;
        for_each_field(m, [&](const mavlink::FieldInfo& info, const auto& field) {
          line += ",";
          line += info.name;
          line += "=";
          line += value_text(field);
        });
      },
      o.message);
  return line + "\n";
}

std::string event_line(HostTime start, const BridgeEvent& e) {
  return fixed6(seconds_since(start, e.time)) + ",event," + std::string(to_string(e.kind)) + "," +
         e.subject + "," + e.text + "\n";
}

/// The scripted vehicle side: what each vehicle says, and when (host seconds after start).
struct Script {
  double t_s;
  std::size_t vehicle;
  ReceivedMessage message;
};

std::vector<Script> vehicle_script() {
  mavlink::Heartbeat px4;
  px4.type = 2;
  px4.autopilot = 12;
  px4.base_mode = 81;
  mavlink::Heartbeat ardupilot;
  ardupilot.type = 10;
  ardupilot.autopilot = 3;
  ardupilot.base_mode = 81 | 128;  // armed
  mavlink::Timesync request;
  request.ts1 = 4'000'000'000;
  mavlink::GpsGlobalOrigin origin;
  origin.latitude = 401156786;
  origin.longitude = -882243507;
  origin.altitude = 222196;
  // Yaw 0: the circle-flying Body2 heads elsewhere → disagreeing, but for less than
  // kAgreementHold by the end of the recording: no verdict (vehicle_state.hpp). The vehicle has
  // been up a minute (past kAgreementSettle).
  mavlink::Attitude attitude;
  attitude.time_boot_ms = 60'000;
  mavlink::LocalPositionNed local;
  local.time_boot_ms = 60'000;
  return {
      {0.35, 0, {1, 1, px4}},   {0.45, 0, {1, 1, request}}, {0.55, 1, {2, 1, ardupilot}},
      {1.35, 0, {1, 1, px4}},   {1.55, 0, {1, 1, origin}},  {2.05, 0, {1, 1, attitude}},
      {2.06, 0, {1, 1, local}},
  };
}

BridgeConfig replay_config() {
  BridgeConfig c;
  c.world = *WorldAxisMapping::parse("+z", "+x");  // the simulator is Vicon-like: +z up
  c.origin = GeodeticPosition{40.1156786, -88.2243507, 222.196};  // the original's Urbana origin
  VehicleSpec quad;
  quad.name = "quad";
  quad.body = "Body2";
  quad.system_id = 1;
  quad.profile = Profile::px4;
  quad.rate_hz = 50.0;
  VehicleSpec rover;
  rover.name = "rover";
  rover.body = "Body1";
  rover.system_id = 2;
  rover.profile = Profile::ardupilot_gps;
  rover.rate_hz = 10.0;
  c.vehicles = {quad, rover};
  return c;
}

std::string run_replay(const wire::Recording& recording) {
  const HostTime start{std::chrono::seconds(1000)};
  auto made = Bridge::make(replay_config(), start);
  if (!std::holds_alternative<Bridge>(made)) {
    ADD_FAILURE() << std::get<BridgeConfigError>(made).message;
    return {};
  }
  Bridge& bridge = std::get<Bridge>(made);
  bridge.set_wall_clock(start, 1'700'000'000'000'000);  // 2023-11-14 22:13:20 UTC
  std::string text =
      "# time_s,vehicle,seq,MESSAGE,field=value... | time_s,event,kind,subject,"
      "text\n";
  auto emit = [&](const BridgeOutput& out) {
    for (const auto& m : out.messages) text += message_line(start, m);
    for (const auto& e : out.events) text += event_line(start, e);
  };
  const auto script = vehicle_script();
  std::size_t next_script = 0;
  HostTime next_tick = start;
  auto advance_to = [&](HostTime t) {
    // Ticks and scripted vehicle messages due before t, in time order.
    while (true) {
      const HostTime script_time =
          next_script < script.size()
              ? start + std::chrono::duration_cast<Duration>(
                            std::chrono::duration<double>(script[next_script].t_s))
              : HostTime::max();
      const HostTime due = std::min(next_tick, script_time);
      if (due > t) break;
      if (next_tick <= script_time) {
        emit(bridge.on_tick(next_tick));
        next_tick += milliseconds(100);
      } else {
        const Script& s = script[next_script++];
        emit(bridge.on_vehicle_message(s.vehicle, s.message, script_time));
      }
    }
  };
  for (const MocapFrame& frame : recording.frames) {
    // Received 4–6 ms after capture (deterministic jitter), 1000 s into the host clock.
    const HostTime received = start + frame.capture_time.time_since_epoch() + milliseconds(4) +
                              milliseconds(static_cast<std::int64_t>(frame.frame_number % 3));
    advance_to(received);
    emit(bridge.on_frame(frame, received));
  }
  return text;
}

/// Lines equal, numbers within 2e-6 (the last printed decimal may differ between compilers'
/// floating-point contraction); everything else exact.
bool same_output(const std::string& expected, const std::string& actual, std::string& where) {
  std::istringstream a(expected);
  std::istringstream b(actual);
  std::string la;
  std::string lb;
  for (int line = 1;; ++line) {
    const bool ga = static_cast<bool>(std::getline(a, la));
    const bool gb = static_cast<bool>(std::getline(b, lb));
    if (!ga && !gb) return true;
    if (ga != gb || la == lb) {
      if (ga != gb) {
        where = "line " + std::to_string(line) + ": one output is longer";
        return false;
      }
      continue;
    }
    // Compare token by token.
    auto split = [](const std::string& s) {
      std::vector<std::string> t;
      std::string cur;
      for (char c : s) {
        if (c == ',' || c == '=' || c == '|') {
          t.push_back(cur);
          cur.clear();
        } else {
          cur += c;
        }
      }
      t.push_back(cur);
      return t;
    };
    const auto ta = split(la);
    const auto tb = split(lb);
    bool ok = ta.size() == tb.size();
    for (std::size_t i = 0; ok && i < ta.size(); ++i) {
      if (ta[i] == tb[i]) continue;
      char* ea = nullptr;
      char* eb = nullptr;
      const double da = std::strtod(ta[i].c_str(), &ea);
      const double db = std::strtod(tb[i].c_str(), &eb);
      ok = *ea == '\0' && *eb == '\0' && !ta[i].empty() && std::abs(da - db) <= 2e-6;
    }
    if (!ok) {
      where = "line " + std::to_string(line) + ":\n  expected: " + la + "\n  actual:   " + lb;
      return false;
    }
  }
}

TEST(ReplayRegression, TwoBodiesTwoVehicles) {
  const std::string csv = read_file(kDir + "/two_bodies.csv");
  ASSERT_FALSE(csv.empty()) << "missing " << kDir << "/two_bodies.csv";
  const auto parsed = wire::parse_recording(csv);
  ASSERT_TRUE(std::holds_alternative<wire::Recording>(parsed))
      << wire::to_string(std::get<wire::RecordingError>(parsed));
  const auto& recording = std::get<wire::Recording>(parsed);
  ASSERT_EQ(recording.frames.size(), 250U);

  const std::string actual = run_replay(recording);
  const std::string expected_path = kDir + "/two_bodies.expected.txt";
  const std::string actual_path = output_dir() + "/two_bodies.actual.txt";
  const std::string expected = read_file(expected_path);
  std::string where;
  if (!same_output(expected, actual, where)) {
    const bool written = static_cast<bool>(std::ofstream(actual_path, std::ios::binary) << actual);
    FAIL() << "replay output differs from " << expected_path << " at " << where
           << (written ? "\nActual output written to " + actual_path
                       : "\nCannot write the actual output to " + actual_path)
           << "\nIf the change is intended, review the diff and accept it with\n  cp "
           << actual_path << " " << expected_path;
  }
  std::remove(actual_path.c_str());
}

}  // namespace
}  // namespace mocaplink::core
