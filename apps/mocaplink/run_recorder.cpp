#include "run_recorder.hpp"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <system_error>
#include <utility>

#include "mocaplink/core/bridge.hpp"
#include "mocaplink/io/file.hpp"
#include "mocaplink/wire/recording_csv.hpp"

namespace mocaplink::app {

std::unique_ptr<Recorder> Recorder::create(const std::filesystem::path& dir,
                                           const std::string& source_url,
                                           const std::vector<std::string>& vehicles,
                                           std::string* problem) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) {
    if (problem != nullptr) *problem = dir.string() + ": " + ec.message();
    return nullptr;
  }
  std::unique_ptr<Recorder> recorder(new Recorder(dir, source_url));
  const auto csv_path = dir / "mocap.csv";
  recorder->csv_ = io::open_file(csv_path, "wb");
  if (recorder->csv_ == nullptr) {
    if (problem != nullptr) {
      *problem =
          csv_path.string() + ": " + std::error_code(errno, std::generic_category()).message();
    }
    return nullptr;
  }
  for (std::size_t slot = 0; slot < vehicles.size(); ++slot) {
    if (!recorder->add_vehicle(slot, vehicles[slot], problem)) return nullptr;
  }
  return recorder;
}

bool Recorder::add_vehicle(std::size_t slot, const std::string& name, std::string* problem) {
  if (slot >= tlogs_.size()) tlogs_.resize(slot + 1);
  const bool again = !opened_.insert(name).second;
  tlogs_[slot] =
      io::TlogWriter::create(dir_ / (name + ".tlog"), problem,
                             again ? io::TlogWriter::Mode::append : io::TlogWriter::Mode::truncate);
  if (!tlogs_[slot]) tlog_failed_ = true;
  return tlogs_[slot] != nullptr;
}

void Recorder::remove_vehicle(std::size_t slot) {
  if (slot >= tlogs_.size() || !tlogs_[slot]) return;
  tlogs_[slot]->close();
  if (tlogs_[slot]->failed()) {
    tlog_failed_ = true;
    // It may end in half a record: a vehicle of that name added again starts the file anew
    // rather than appending after it.
    opened_.erase(tlogs_[slot]->path().stem().string());
  }
  tlogs_[slot].reset();
  while (!tlogs_.empty() && !tlogs_.back()) tlogs_.pop_back();
}

Recorder::Recorder(std::filesystem::path dir, std::string source_url)
    : dir_(std::move(dir)), source_url_(std::move(source_url)) {}

Recorder::~Recorder() {
  close();
}

void Recorder::write_header(std::optional<double> rate_hz) {
  if (header_written_ || csv_ == nullptr) return;
  header_written_ = true;
  const std::string header = wire::format_recording_header(source_url_, rate_hz);
  if (std::fwrite(header.data(), 1, header.size(), csv_) != header.size()) csv_failed_ = true;
}

void Recorder::on_frame(const core::MocapFrame& frame, core::HostTime received, FrameFate fate) {
  if (csv_ == nullptr || csv_failed_) return;
  core::SourceTime capture = frame.capture_time + capture_offset_;
  if (last_capture_ && last_received_ &&
      core::source_clock_restarted(*last_capture_, *last_received_, capture, received,
                                   restart_step_back_)) {
    // The source's clock started again: go on from the last frame, after the outage (at least
    // the format's 1 µs, so the restart frame is a frame of its own).
    const core::Duration gap =
        std::max<core::Duration>(received - *last_received_, std::chrono::microseconds(1));
    capture_offset_ = *last_capture_ + gap - frame.capture_time;
    capture = frame.capture_time + capture_offset_;
  }
  last_received_ = received;
  if (last_capture_ && capture < *last_capture_) {
    ++frames_skipped_;
    return;
  }
  write_header(frame.frame_rate_hz);
  if (!first_capture_) first_capture_ = capture;
  last_capture_ = capture;
  std::optional<std::string_view> comment;
  if (fate == FrameFate::late) comment = kLateComment;
  if (fate == FrameFate::superseded) comment = kSupersededComment;
  // time_s = capture - first = frame.capture_time - (first - offset): no copy of the frame.
  const std::string rows =
      wire::format_recording_frame(frame, *first_capture_ - capture_offset_, comment);
  if (std::fwrite(rows.data(), 1, rows.size(), csv_) != rows.size()) {
    csv_failed_ = true;
    return;
  }
  ++frames_written_;
  if (comment) ++frames_not_sent_;
}

void Recorder::on_mavlink(std::size_t vehicle, std::int64_t unix_us,
                          std::span<const std::uint8_t> bytes) {
  if (vehicle < tlogs_.size() && tlogs_[vehicle]) tlogs_[vehicle]->write(unix_us, bytes);
}

void Recorder::flush() {
  if (csv_ != nullptr && !csv_failed_ && std::fflush(csv_) != 0) csv_failed_ = true;
  for (auto& tlog : tlogs_) {
    if (tlog) tlog->flush();
  }
}

void Recorder::close() {
  if (csv_ != nullptr) {
    write_header(std::nullopt);  // a run without frames still leaves a readable recording
    flush();
    if (std::fclose(csv_) != 0) csv_failed_ = true;
    csv_ = nullptr;
  }
  for (auto& tlog : tlogs_) {
    if (tlog) tlog->close();
  }
}

bool Recorder::failed() const noexcept {
  if (csv_failed_ || tlog_failed_) return true;
  for (const auto& tlog : tlogs_) {
    if (tlog && tlog->failed()) return true;
  }
  return false;
}

}  // namespace mocaplink::app
