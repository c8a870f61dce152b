#include "mocaplink/io/tlog.hpp"

#include <cerrno>
#include <cstring>
#include <system_error>
#include <utility>

#include "mocaplink/io/file.hpp"

namespace mocaplink::io {
namespace {
constexpr std::size_t kBufferBytes = 64 * 1024;
}  // namespace

std::array<std::uint8_t, 8> tlog_time_prefix(std::int64_t unix_us) noexcept {
  const auto value = static_cast<std::uint64_t>(unix_us);
  std::array<std::uint8_t, 8> out{};
  for (std::size_t i = 0; i < out.size(); ++i) {
    out[i] = static_cast<std::uint8_t>(value >> (8 * (7 - i)));
  }
  return out;
}

std::unique_ptr<TlogWriter> TlogWriter::create(const std::filesystem::path& path,
                                               std::string* problem, Mode mode) {
  std::FILE* file = open_file(path, mode == Mode::append ? "ab" : "wb");
  if (file == nullptr) {
    if (problem != nullptr) {
      *problem = path.string() + ": " + std::error_code(errno, std::generic_category()).message();
    }
    return nullptr;
  }
  return std::unique_ptr<TlogWriter>(new TlogWriter(file, path));
}

TlogWriter::TlogWriter(std::FILE* file, std::filesystem::path path)
    : file_(file), path_(std::move(path)), buffer_(std::make_unique<char[]>(kBufferBytes)) {
  std::setvbuf(file_, buffer_.get(), _IOFBF, kBufferBytes);
}

TlogWriter::~TlogWriter() {
  close();
}

void TlogWriter::write(std::int64_t unix_us, std::span<const std::uint8_t> frame) noexcept {
  if (file_ == nullptr || failed_) return;
  const auto prefix = tlog_time_prefix(unix_us);
  if (std::fwrite(prefix.data(), 1, prefix.size(), file_) != prefix.size() ||
      std::fwrite(frame.data(), 1, frame.size(), file_) != frame.size()) {
    failed_ = true;
    return;
  }
  ++records_;
  bytes_ += prefix.size() + frame.size();
}

void TlogWriter::flush() noexcept {
  if (file_ != nullptr && !failed_ && std::fflush(file_) != 0) failed_ = true;
}

void TlogWriter::close() noexcept {
  if (file_ == nullptr) return;
  flush();
  if (std::fclose(file_) != 0) failed_ = true;
  file_ = nullptr;
}

}  // namespace mocaplink::io
