// Recording CSV (DESIGN.md "Recording format"): golden rows written by hand, every rejection with
// its line number, and the exact text the writer produces.
#include "mocaplink/wire/recording_csv.hpp"

#include <string>
#include <variant>

#include <gtest/gtest.h>

namespace mocaplink::wire {
namespace {

Recording parse_ok(std::string_view text) {
  auto result = parse_recording(text);
  if (auto* error = std::get_if<RecordingError>(&result)) {
    ADD_FAILURE() << to_string(*error);
    return {};
  }
  return std::get<Recording>(std::move(result));
}

RecordingError parse_error(std::string_view text) {
  auto result = parse_recording(text);
  if (auto* error = std::get_if<RecordingError>(&result)) return *error;
  ADD_FAILURE() << "accepted: " << text;
  return {};
}

constexpr std::string_view kHeader =
    "# mocaplink recording 1; source=vicon://192.168.1.3; rate_hz=200\n"
    "time_s,frame,body,tracked,x_m,y_m,z_m,qw,qx,qy,qz\n";

TEST(RecordingCsv, ReadsTheDesignExampleAndGroupsRowsIntoFrames) {
  const std::string text = std::string(kHeader) +
                           "0.000000,1,Quad1,1,0.123400,-1.500000,0.800000,1.000000,0.000000,"
                           "0.000000,0.000000\n"
                           "0.000000,1,Quad2,0,,,,,,,\n"
                           "0.005000,2,Quad1,1,0.1235,-1.5,0.8,0.707107,0,0,0.707107\n"
                           "# a comment between frames\n"
                           "\n"
                           "0.010000,4,Quad1,0,garbage,is,ignored,when,untracked,x,y\n";
  const Recording rec = parse_ok(text);
  EXPECT_EQ(rec.header.source, "vicon://192.168.1.3");
  ASSERT_TRUE(rec.header.rate_hz.has_value());
  EXPECT_EQ(*rec.header.rate_hz, 200.0);
  ASSERT_EQ(rec.frames.size(), 3u);

  const auto& f1 = rec.frames[0];
  EXPECT_EQ(f1.frame_number, 1u);
  EXPECT_EQ(f1.capture_time.time_since_epoch().count(), 0);
  EXPECT_EQ(f1.frame_rate_hz, 200.0);
  ASSERT_EQ(f1.bodies.size(), 2u);
  EXPECT_EQ(f1.bodies[0].name, "Quad1");
  EXPECT_TRUE(f1.bodies[0].tracked);
  EXPECT_EQ(f1.bodies[0].p_world_m, Eigen::Vector3d(0.1234, -1.5, 0.8));
  EXPECT_EQ(f1.bodies[0].q_world_body.w(), 1.0);
  EXPECT_EQ(f1.bodies[1].name, "Quad2");
  EXPECT_FALSE(f1.bodies[1].tracked);

  const auto& f2 = rec.frames[1];
  EXPECT_EQ(f2.frame_number, 2u);
  EXPECT_EQ(f2.capture_time.time_since_epoch().count(), 5'000'000);  // 5 ms in ns
  // 90° about z, normalised (0.707107² · 2 = 1.0000011).
  EXPECT_NEAR(f2.bodies[0].q_world_body.w(), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(f2.bodies[0].q_world_body.z(), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(f2.bodies[0].q_world_body.norm(), 1.0, 1e-15);

  EXPECT_EQ(rec.frames[2].frame_number, 4u);  // a gap is kept: that is what drops look like
  EXPECT_FALSE(rec.frames[2].bodies[0].tracked);
}

TEST(RecordingCsv, AcceptsCrlfBlanksQuotesAndNoHeaderComment) {
  const Recording rec = parse_ok(
      "time_s,frame,body,tracked,x_m,y_m,z_m,qw,qx,qy,qz\r\n"
      " 1.5 , 7 , \"Arm, left \"\"A\"\"\" , 1 , 1 , 2 , 3 , 1 , 0 , 0 , 0 \r\n");
  EXPECT_EQ(rec.header.source, "");
  EXPECT_FALSE(rec.header.rate_hz.has_value());
  ASSERT_EQ(rec.frames.size(), 1u);
  EXPECT_FALSE(rec.frames[0].frame_rate_hz.has_value());
  EXPECT_EQ(rec.frames[0].capture_time.time_since_epoch().count(), 1'500'000'000);
  EXPECT_EQ(rec.frames[0].frame_number, 7u);
  EXPECT_EQ(rec.frames[0].bodies[0].name, "Arm, left \"A\"");
  EXPECT_EQ(rec.frames[0].bodies[0].p_world_m, Eigen::Vector3d(1, 2, 3));
}

TEST(RecordingCsv, FrameCounterRestartsAreAllowed) {
  const Recording rec = parse_ok(std::string(kHeader) +
                                 "0.0,1000,A,1,0,0,0,1,0,0,0\n"
                                 "0.1,1,A,1,0,0,0,1,0,0,0\n");
  ASSERT_EQ(rec.frames.size(), 2u);
  EXPECT_EQ(rec.frames[1].frame_number, 1u);
}

TEST(RecordingCsv, EmptyRecordingWithOnlyAHeaderHasNoFrames) {
  EXPECT_TRUE(parse_ok(kHeader).frames.empty());
}

struct BadCase {
  const char* what;
  std::string text;
  std::size_t line;
  const char* message_part;
};

TEST(RecordingCsv, RejectsBadInputWithTheLineNumber) {
  const std::string h(kHeader);  // two lines
  const BadCase cases[] = {
      {"missing column line", "0.0,1,A,1,0,0,0,1,0,0,0\n", 1, "expected the column line"},
      {"empty file", "", 0, "no column line"},
      {"only comments", "# hello\n# there\n", 2, "no column line"},
      {"too few columns", h + "0.0,1,A,1,0,0,0,1,0,0\n", 3, "expected 11 columns, found 10"},
      {"too many columns", h + "0.0,1,A,1,0,0,0,1,0,0,0,9\n", 3, "found 12"},
      {"non-numeric x", h + "0.0,1,A,1,abc,0,0,1,0,0,0\n", 3, "column x_m: 'abc'"},
      {"NaN in tracked row", h + "0.0,1,A,1,0,nan,0,1,0,0,0\n", 3, "column y_m: 'nan'"},
      {"inf time", h + "inf,1,A,1,0,0,0,1,0,0,0\n", 3, "column time_s"},
      {"empty pose in tracked row", h + "0.0,1,A,1,,,,,,,\n", 3, "column x_m: ''"},
      {"negative frame", h + "0.0,-1,A,1,0,0,0,1,0,0,0\n", 3, "column frame"},
      {"frame beyond 2^64", h + "0.0,18446744073709551616,A,0,,,,,,,\n", 3, "column frame"},
      {"tracked not 0/1", h + "0.0,1,A,yes,0,0,0,1,0,0,0\n", 3, "column tracked: 'yes'"},
      {"empty name", h + "0.0,1,,1,0,0,0,1,0,0,0\n", 3, "empty name"},
      {"control character in name", h + "0.0,1,\"A\rB\",0,,,,,,,\n", 3, "control character"},
      {"NUL in name", h + std::string("0.0,1,A\0B,0,,,,,,,\n", 19), 3, "control character"},
      {"zero quaternion", h + "0.0,1,A,1,0,0,0,0,0,0,0\n", 3, "quaternion norm"},
      {"duplicate body", h + "0.0,1,A,0,,,,,,,\n0.0,1,A,0,,,,,,,\n", 4, "twice"},
      {"time differs in frame", h + "0.0,1,A,0,,,,,,,\n0.1,1,B,0,,,,,,,\n", 4, "time_s"},
      {"time goes back", h + "0.2,1,A,0,,,,,,,\n0.1,2,A,0,,,,,,,\n", 4, "earlier"},
      {"unterminated quote", h + "0.0,1,\"A,0,,,,,,,\n", 3, "unterminated"},
      {"text after quote", h + "0.0,1,\"A\"x,0,,,,,,,\n", 3, "after a closing quote"},
      {"bad version", "# mocaplink recording 2; source=x\n" + h, 1, "version '2'"},
      {"bad header rate", "# mocaplink recording 1; rate_hz=fast\n", 1, "rate_hz='fast'"},
      {"huge line", h + std::string(5000, '1') + "\n", 3, "longer than 4096"},
  };
  for (const auto& c : cases) {
    const RecordingError error = parse_error(c.text);
    EXPECT_EQ(error.line, c.line) << c.what << ": " << to_string(error);
    EXPECT_NE(error.message.find(c.message_part), std::string::npos)
        << c.what << ": " << to_string(error);
  }
}

TEST(RecordingCsv, ReaderStaysFailedAfterAnError) {
  RecordingReader reader;
  ASSERT_TRUE(std::holds_alternative<RecordingError>(reader.feed_line("nonsense")));
  const auto again = reader.feed_line(std::string(kRecordingColumns));
  ASSERT_TRUE(std::holds_alternative<RecordingError>(again));
  EXPECT_EQ(std::get<RecordingError>(again).line, 1u);
  EXPECT_TRUE(std::holds_alternative<RecordingError>(reader.finish()));
}

TEST(RecordingCsv, BodyLimitPerFrameIsEnforced) {
  std::string text(kHeader);
  for (std::size_t i = 0; i <= kMaxRecordingBodies; ++i) {
    text += "0.0,1,B" + std::to_string(i) + ",0,,,,,,,\n";
  }
  const RecordingError error = parse_error(text);
  EXPECT_EQ(error.line, 2 + kMaxRecordingBodies + 1);
  EXPECT_NE(error.message.find("more than 1024 bodies"), std::string::npos);
}

TEST(RecordingCsv, WritesTheExactTextOfTheFormat) {
  EXPECT_EQ(format_recording_header("sim://?bodies=2", 200.0),
            "# mocaplink recording 1; source=sim://?bodies=2; rate_hz=200\n"
            "time_s,frame,body,tracked,x_m,y_m,z_m,qw,qx,qy,qz\n");
  EXPECT_EQ(format_recording_header("replay://a.csv", std::nullopt),
            "# mocaplink recording 1; source=replay://a.csv\n"
            "time_s,frame,body,tracked,x_m,y_m,z_m,qw,qx,qy,qz\n");

  core::MocapFrame frame;
  frame.frame_number = 42;
  frame.capture_time = core::source_time_from_ns(10'250'000'400);  // 0.25 s after the first
  core::BodySample quad;
  quad.name = "Quad1";
  quad.tracked = true;
  quad.p_world_m = {0.1234, -1.5, 0.8};
  quad.q_world_body = Eigen::Quaterniond(0.0, 0.0, 0.0, 1.0);  // 180° about z
  core::BodySample odd;
  odd.name = "a,\"b\"\nc";
  odd.tracked = true;
  odd.p_world_m = {std::nan(""), 0.0, 0.0};  // a broken source: written as untracked
  frame.bodies = {quad, odd};
  EXPECT_EQ(format_recording_frame(frame, core::source_time_from_ns(10'000'000'000)),
            "0.250000,42,Quad1,1,0.123400,-1.500000,0.800000,0.000000,0.000000,0.000000,1.000000\n"
            "0.250000,42,\"a,\"\"b\"\"?c\",0,,,,,,,\n");
}

TEST(RecordingCsv, WrittenFramesReadBack) {
  core::MocapFrame frame;
  frame.frame_number = 9;
  core::BodySample body;
  body.name = " spaced \"name\" ";
  body.tracked = true;
  body.p_world_m = {-3.25, 0.000001, 1e3};
  body.q_world_body = Eigen::Quaterniond(0.5, -0.5, 0.5, 0.5);
  frame.bodies = {body};
  const std::string text = format_recording_header("x", 100.0) + format_recording_frame(frame, {});
  const Recording rec = parse_ok(text);
  ASSERT_EQ(rec.frames.size(), 1u);
  const auto& got = rec.frames[0].bodies.at(0);
  EXPECT_EQ(got.name, body.name);
  EXPECT_TRUE(got.p_world_m.isApprox(body.p_world_m, 1e-9));
  EXPECT_TRUE(got.q_world_body.coeffs().isApprox(body.q_world_body.coeffs(), 1e-9));
  EXPECT_EQ(rec.frames[0].frame_rate_hz, 100.0);
}

TEST(RecordingCsv, AFrameWrittenAsACommentIsKeptButNotRead) {
  core::MocapFrame frame;
  frame.frame_number = 7;
  core::BodySample a;
  a.name = "A";
  core::BodySample b;
  b.name = "B";
  frame.bodies = {a, b};
  const std::string rows = format_recording_frame(frame, {}, " late: ");
  EXPECT_EQ(rows, "# late: 0.000000,7,A,0,,,,,,,\n# late: 0.000000,7,B,0,,,,,,,\n");
  frame.frame_number = 8;
  const Recording rec =
      parse_ok(format_recording_header("x", 100.0) + rows + format_recording_frame(frame, {}));
  ASSERT_EQ(rec.frames.size(), 1u);  // only the frame written as rows
  EXPECT_EQ(rec.frames[0].frame_number, 8u);
}

}  // namespace
}  // namespace mocaplink::wire
