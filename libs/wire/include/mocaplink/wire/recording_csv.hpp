// The mocaplink recording format (DESIGN.md "Recording format"): plain CSV that `mocaplink record`
// writes and `replay://` reads.
//
//   # mocaplink recording 1; source=vicon://192.168.1.3; rate_hz=200
//   time_s,frame,body,tracked,x_m,y_m,z_m,qw,qx,qy,qz
//   0.000000,1,Quad1,1,0.123400,-1.500000,0.800000,1.000000,0.000000,0.000000,0.000000
//
// One row per body per frame; consecutive rows with the same frame number form one frame. time_s
// is the capture time on the source's clock, seconds from the first frame; positions are metres and
// the quaternion (w first) rotates body vectors into the source's world frame, before any axis
// mapping. tracked = 0 marks an occluded body: its pose columns are ignored (record leaves them
// empty).
//
// Reading rules (recordings come from outside — other machines, spreadsheets, hand edits):
//   - lines starting with '#' and blank lines are skipped; a trailing '\r' is accepted (CRLF);
//     spaces and tabs around a field are ignored; a field may be double-quoted ("a,b", "say
//     ""x""");
//   - the first `# mocaplink recording V; key=value; ...` comment, if any, must have V = 1 and
//   gives
//     source= and rate_hz= (other keys are ignored, for forward compatibility);
//   - the column line above must come before the first row;
//   - every row has exactly 11 fields; frame is a decimal integer in [0, 2^64); tracked is 0 or 1;
//     time_s and, in tracked rows, the pose are finite decimal numbers; the quaternion's norm must
//     be within 1e-3 of 1 and is normalised;
//   - a body name is 1..kMaxBodyNameBytes bytes without ASCII control characters;
//   - within a frame, time_s is the same on every row and body names are unique; from frame to
//     frame time_s never decreases (frame numbers may restart, as after a server restart);
//   - bounds: a line has at most kMaxRecordingLineBytes bytes, a name kMaxBodyNameBytes, a frame
//     kMaxRecordingBodies bodies.
// Any violation is a RecordingError naming the 1-based line; the reader never throws or aborts.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "mocaplink/core/mocap_frame.hpp"
#include "mocaplink/core/time.hpp"

namespace mocaplink::wire {

/// The column line, exactly as written.
inline constexpr std::string_view kRecordingColumns =
    "time_s,frame,body,tracked,x_m,y_m,z_m,qw,qx,qy,qz";
inline constexpr std::size_t kMaxRecordingLineBytes = 4096;
inline constexpr std::size_t kMaxBodyNameBytes = 256;
inline constexpr std::size_t kMaxRecordingBodies = 1024;

/// Why a recording was rejected: 1-based line number (0 when no line was read) and a reason that
/// names the column and the offending text.
struct RecordingError {
  std::size_t line = 0;
  std::string message;
};

/// "line 7: column x_m: 'abc' is not a number".
[[nodiscard]] std::string to_string(const RecordingError& error);

/// What the header comment says; both fields empty when it is absent.
struct RecordingHeader {
  std::string source;             ///< the recorded source's URL
  std::optional<double> rate_hz;  ///< the source's nominal frame rate, > 0
};

/// Result of feeding one line: a completed frame, nothing yet, or the first error.
using RecordingStep = std::variant<std::optional<core::MocapFrame>, RecordingError>;

/// Incremental reader: feed lines in order, then finish(). Memory is bounded by one frame, so
/// recordings of any length can be replayed. Frames come out with frame_number, capture_time
/// (time_s after the source clock's epoch), frame_rate_hz (the header's rate_hz, if any) and
/// bodies in file order; source_latency is not recorded. After an error the reader stays failed
/// and returns that error again. Not thread-safe (one reader per file).
class RecordingReader {
 public:
  /// One line, without its '\n'. Returns the previous frame when this line starts a new one.
  [[nodiscard]] RecordingStep feed_line(std::string_view line);
  /// End of input: the last frame (if any), or an error if the column line never came.
  [[nodiscard]] RecordingStep finish();

  [[nodiscard]] const RecordingHeader& header() const { return header_; }
  /// Whether the column line has been read (so the header comment, if any, too).
  [[nodiscard]] bool header_complete() const { return seen_columns_; }
  /// Lines fed so far.
  [[nodiscard]] std::size_t line_number() const { return line_; }

 private:
  [[nodiscard]] RecordingStep fail(std::string message);
  [[nodiscard]] RecordingStep feed_comment(std::string_view comment);
  [[nodiscard]] RecordingStep feed_row(std::string_view line);

  RecordingHeader header_;
  std::size_t line_ = 0;
  bool seen_comment_ = false;
  bool seen_columns_ = false;
  std::optional<RecordingError> error_;
  std::optional<core::MocapFrame> current_;
  std::optional<core::SourceTime> last_time_;
};

/// A whole recording in memory (tests, fuzzing, small files).
struct Recording {
  RecordingHeader header;
  std::vector<core::MocapFrame> frames;
};

/// Parses a whole text ('\n' or "\r\n" line ends). Pure; thread-safe.
[[nodiscard]] std::variant<Recording, RecordingError> parse_recording(std::string_view text);

/// The header comment and the column line, each ending in '\n'. rate_hz is omitted when unknown.
[[nodiscard]] std::string format_recording_header(std::string_view source,
                                                  std::optional<double> rate_hz);

/// The rows of one frame, each ending in '\n'; time_s = capture_time − first_capture. Numbers have
/// 6 decimals (1 µm, 1 µs). A name with ',' or '"' is quoted; control characters in a name
/// (CR, LF, NUL, ...) become '?' (the format is line-based), an empty name is written '?' and
/// names are cut to kMaxBodyNameBytes. A tracked body with a non-finite pose is written as
/// untracked, so that every written file reads back. With a `comment`, every row is written as a
/// comment line, '#' + comment + the row: kept in the file, skipped by the reader (run --record
/// writes a frame it did not send so).
[[nodiscard]] std::string format_recording_frame(const core::MocapFrame& frame,
                                                 core::SourceTime first_capture,
                                                 std::optional<std::string_view> comment = {});

}  // namespace mocaplink::wire
