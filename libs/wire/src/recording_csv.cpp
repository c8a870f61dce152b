#include "mocaplink/wire/recording_csv.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <system_error>
#include <utility>

namespace mocaplink::wire {
namespace {

constexpr std::size_t kColumns = 11;
constexpr std::array<std::string_view, kColumns> kColumnNames{
    "time_s", "frame", "body", "tracked", "x_m", "y_m", "z_m", "qw", "qx", "qy", "qz"};
constexpr double kQuaternionNormTolerance = 1e-3;

/// ASCII control characters (incl. NUL, CR, LF, DEL): never part of a body name.
bool is_control(char c) {
  const auto u = static_cast<unsigned char>(c);
  return u < 0x20 || u == 0x7f;
}

std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t");
  return s.substr(first, last - first + 1);
}

/// Splits one CSV line into fields (RFC 4180 quoting within the line). Fills `out` with at most
/// kColumns + 1 fields (enough to tell "too many"); returns an error message or "".
std::string split_fields(std::string_view line, std::vector<std::string>& out, std::size_t& count) {
  out.clear();
  count = 0;
  std::size_t i = 0;
  while (true) {
    std::string field;
    // Skip leading blanks so that ` "a,b"` is still a quoted field.
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    if (i < line.size() && line[i] == '"') {
      ++i;
      bool closed = false;
      while (i < line.size()) {
        if (line[i] == '"') {
          if (i + 1 < line.size() && line[i + 1] == '"') {
            field.push_back('"');
            i += 2;
            continue;
          }
          closed = true;
          ++i;
          break;
        }
        field.push_back(line[i]);
        ++i;
      }
      if (!closed) return "unterminated quoted field";
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
      if (i < line.size() && line[i] != ',') return "text after a closing quote";
    } else {
      const auto comma = line.find(',', i);
      const auto end = comma == std::string_view::npos ? line.size() : comma;
      field = std::string(trim(line.substr(i, end - i)));
      i = end;
    }
    ++count;
    if (out.size() <= kColumns) out.push_back(std::move(field));
    if (i >= line.size()) return {};
    ++i;  // the comma
  }
}

template <typename T>
bool parse_number(std::string_view text, T& out) {
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, out);
  if (ec != std::errc{} || ptr != end || text.empty()) return false;
  if constexpr (std::is_floating_point_v<T>) return std::isfinite(out);
  return true;
}

std::string quoted(std::string_view text) {
  constexpr std::size_t kShown = 40;  // keep messages readable for absurd inputs
  // Appended piece by piece: GCC 12 at -O2 and above reports a false -Wrestrict for
  // `"'" + std::string(...)` (operator+ inserting at the front of its right operand).
  const std::string_view shown = text.substr(0, kShown);
  std::string out;
  out.reserve(shown.size() + 5);
  out += '\'';
  out += shown;
  if (text.size() > kShown) out += "...";
  out += '\'';
  return out;
}

void append_fixed6(std::string& out, double value) {
  std::array<char, 64> buf{};
  const auto [ptr, ec] =
      std::to_chars(buf.data(), buf.data() + buf.size(), value, std::chars_format::fixed, 6);
  if (ec != std::errc{}) {
    out += "0.000000";  // only for |value| > 1e57, which the callers never pass (finite poses)
    return;
  }
  out.append(buf.data(), ptr);
}

std::string escape_name(std::string_view name) {
  std::string clean(name.substr(0, kMaxBodyNameBytes));
  // An empty field would not read back. push_back, not `= "?"`: GCC 12 at -O2 and above reports
  // a false -Wrestrict for assigning the literal here.
  if (clean.empty()) clean.push_back('?');
  std::replace_if(clean.begin(), clean.end(), is_control, '?');
  if (clean.find_first_of(",\"") == std::string::npos && trim(clean) == clean) return clean;
  std::string out = "\"";
  for (char c : clean) {
    if (c == '"') out.push_back('"');
    out.push_back(c);
  }
  return out + "\"";
}

}  // namespace

std::string to_string(const RecordingError& error) {
  return "line " + std::to_string(error.line) + ": " + error.message;
}

RecordingStep RecordingReader::fail(std::string message) {
  error_ = RecordingError{line_, std::move(message)};
  return *error_;
}

RecordingStep RecordingReader::feed_line(std::string_view line) {
  if (error_) return *error_;
  ++line_;
  if (line.size() > kMaxRecordingLineBytes) {
    return fail("line longer than " + std::to_string(kMaxRecordingLineBytes) + " bytes");
  }
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  const std::string_view content = trim(line);
  if (content.empty()) return std::optional<core::MocapFrame>{};
  if (content.front() == '#') return feed_comment(content.substr(1));
  if (!seen_columns_) {
    if (content != kRecordingColumns) {
      return fail("expected the column line '" + std::string(kRecordingColumns) +
                  "' before any data, found " + quoted(content));
    }
    seen_columns_ = true;
    return std::optional<core::MocapFrame>{};
  }
  return feed_row(line);
}

RecordingStep RecordingReader::feed_comment(std::string_view comment) {
  constexpr std::string_view kMagic = "mocaplink recording ";
  comment = trim(comment);
  if (seen_comment_ || seen_columns_ || comment.substr(0, kMagic.size()) != kMagic) {
    return std::optional<core::MocapFrame>{};  // an ordinary comment
  }
  seen_comment_ = true;
  comment.remove_prefix(kMagic.size());
  bool first = true;
  while (!comment.empty()) {
    const auto semi = comment.find(';');
    const std::string_view part = trim(comment.substr(0, semi));
    comment = semi == std::string_view::npos ? std::string_view{} : comment.substr(semi + 1);
    if (first) {
      first = false;
      if (part != "1") return fail("unsupported recording version " + quoted(part) + " (want 1)");
      continue;
    }
    const auto eq = part.find('=');
    if (eq == std::string_view::npos) continue;
    const std::string_view key = trim(part.substr(0, eq));
    const std::string_view value = trim(part.substr(eq + 1));
    if (key == "source") {
      header_.source = std::string(value.substr(0, kMaxRecordingLineBytes));
    } else if (key == "rate_hz") {
      double rate_hz = 0.0;
      if (!parse_number(value, rate_hz) || rate_hz <= 0.0) {
        return fail("header rate_hz=" + quoted(value) + " is not a positive number");
      }
      header_.rate_hz = rate_hz;
    }
  }
  if (first) return fail("header comment has no recording version");
  return std::optional<core::MocapFrame>{};
}

RecordingStep RecordingReader::feed_row(std::string_view line) {
  std::vector<std::string> fields;
  std::size_t count = 0;
  if (auto problem = split_fields(line, fields, count); !problem.empty()) return fail(problem);
  if (count != kColumns) {
    return fail("expected " + std::to_string(kColumns) + " columns, found " +
                std::to_string(count));
  }
  const auto bad_number = [&](std::size_t column) {
    return fail("column " + std::string(kColumnNames[column]) + ": " + quoted(fields[column]) +
                " is not a finite number");
  };
  double time_s = 0.0;
  if (!parse_number(fields[0], time_s)) return bad_number(0);
  // Whole nanoseconds, as every source clock; |time_s| < ~292 years fits in int64 ns.
  if (std::fabs(time_s) > 9.0e9) return fail("column time_s: " + quoted(fields[0]) + " too large");
  const core::SourceTime capture = core::source_time_from_ns(std::llround(time_s * 1e9));
  std::uint64_t frame_number = 0;
  if (!parse_number(fields[1], frame_number)) {
    return fail("column frame: " + quoted(fields[1]) + " is not an integer in [0, 2^64)");
  }
  core::BodySample body;
  body.name = fields[2];
  if (body.name.empty()) return fail("column body: empty name");
  if (std::any_of(body.name.begin(), body.name.end(), is_control)) {
    return fail("column body: control character in name " + quoted(body.name));
  }
  if (body.name.size() > kMaxBodyNameBytes) {
    return fail("column body: name longer than " + std::to_string(kMaxBodyNameBytes) + " bytes");
  }
  if (fields[3] != "0" && fields[3] != "1") {
    return fail("column tracked: " + quoted(fields[3]) + " is not 0 or 1");
  }
  body.tracked = fields[3] == "1";
  if (body.tracked) {
    std::array<double, 7> pose{};
    for (std::size_t k = 0; k < pose.size(); ++k) {
      if (!parse_number(fields[4 + k], pose[k])) return bad_number(4 + k);
    }
    body.p_world_m = {pose[0], pose[1], pose[2]};
    const Eigen::Quaterniond q(pose[3], pose[4], pose[5], pose[6]);
    if (!(std::fabs(q.norm() - 1.0) <= kQuaternionNormTolerance)) {
      return fail("quaternion norm " + std::to_string(q.norm()) + " is not 1");
    }
    body.q_world_body = q.normalized();
  }

  std::optional<core::MocapFrame> completed;
  if (current_ && current_->frame_number == frame_number) {
    if (current_->capture_time != capture) {
      return fail("frame " + std::to_string(frame_number) + " has time_s " + fields[0] +
                  " but its first row had another");
    }
    if (current_->bodies.size() >= kMaxRecordingBodies) {
      return fail("more than " + std::to_string(kMaxRecordingBodies) + " bodies in one frame");
    }
    for (const auto& other : current_->bodies) {
      if (other.name == body.name) return fail("body " + quoted(body.name) + " twice in a frame");
    }
  } else {
    if (last_time_ && capture < *last_time_) {
      return fail("time_s " + fields[0] + " is earlier than the previous frame's");
    }
    completed = std::move(current_);
    current_.emplace();
    current_->frame_number = frame_number;
    current_->capture_time = capture;
    current_->frame_rate_hz = header_.rate_hz;
    last_time_ = capture;
  }
  current_->bodies.push_back(std::move(body));
  return completed;
}

RecordingStep RecordingReader::finish() {
  if (error_) return *error_;
  if (!seen_columns_) {
    return fail("no column line '" + std::string(kRecordingColumns) + "': not a recording");
  }
  std::optional<core::MocapFrame> last = std::move(current_);
  current_.reset();
  return last;
}

std::variant<Recording, RecordingError> parse_recording(std::string_view text) {
  RecordingReader reader;
  Recording out;
  const auto take = [&](RecordingStep step) -> std::optional<RecordingError> {
    if (auto* error = std::get_if<RecordingError>(&step)) return *error;
    auto& frame = std::get<std::optional<core::MocapFrame>>(step);
    if (frame) out.frames.push_back(std::move(*frame));
    return std::nullopt;
  };
  while (!text.empty()) {
    const auto newline = text.find('\n');
    const std::string_view line = text.substr(0, newline);
    text = newline == std::string_view::npos ? std::string_view{} : text.substr(newline + 1);
    if (auto error = take(reader.feed_line(line))) return *error;
  }
  if (auto error = take(reader.finish())) return *error;
  out.header = reader.header();
  return out;
}

std::string format_recording_header(std::string_view source, std::optional<double> rate_hz) {
  std::string out = "# mocaplink recording 1; source=";
  for (char c : source) out.push_back(c == '\n' || c == '\r' || c == ';' ? '?' : c);
  if (rate_hz && std::isfinite(*rate_hz) && *rate_hz > 0.0) {
    out += "; rate_hz=";
    // Shortest text that reads back to the same double.
    std::array<char, 64> buf{};
    const auto [ptr, ec] = std::to_chars(buf.data(), buf.data() + buf.size(), *rate_hz);
    if (ec == std::errc{}) out.append(buf.data(), ptr);
  }
  out += '\n';
  out += kRecordingColumns;
  out += '\n';
  return out;
}

std::string format_recording_frame(const core::MocapFrame& frame, core::SourceTime first_capture,
                                   std::optional<std::string_view> comment) {
  std::string out;
  std::string prefix;
  if (comment) prefix.append("#").append(*comment);
  append_fixed6(prefix, core::to_seconds(frame.capture_time - first_capture));
  prefix += ',' + std::to_string(frame.frame_number) + ',';
  for (const auto& body : frame.bodies) {
    const bool finite = body.p_world_m.allFinite() && body.q_world_body.coeffs().allFinite() &&
                        body.q_world_body.norm() > 0.5;
    const bool tracked = body.tracked && finite;
    out += prefix;
    out += escape_name(body.name);
    out += tracked ? ",1" : ",0";
    if (!tracked) {
      out += ",,,,,,,\n";
      continue;
    }
    const Eigen::Quaterniond q = body.q_world_body.normalized();
    for (double v :
         {body.p_world_m.x(), body.p_world_m.y(), body.p_world_m.z(), q.w(), q.x(), q.y(), q.z()}) {
      out += ',';
      append_fixed6(out, v);
    }
    out += '\n';
  }
  return out;
}

}  // namespace mocaplink::wire
