#include "mocaplink/io/rotating_file.hpp"

#include <cerrno>
#include <cstring>
#include <system_error>
#include <utility>

#include "mocaplink/io/file.hpp"

namespace mocaplink::io {

RotatingFile::RotatingFile(std::filesystem::path path, std::size_t max_bytes, std::size_t keep)
    : path_(std::move(path)), max_bytes_(max_bytes), keep_(keep) {
  std::error_code ec;
  if (path_.has_parent_path()) std::filesystem::create_directories(path_.parent_path(), ec);
  if (ec) {
    error_ = "cannot create " + path_.parent_path().string() + ": " + ec.message();
    return;
  }
  open("ab");
}

RotatingFile::~RotatingFile() {
  if (file_ != nullptr) std::fclose(file_);
}

std::filesystem::path RotatingFile::older(std::size_t k) const {
  return path_.parent_path() /
         (path_.stem().string() + "." + std::to_string(k) + path_.extension().string());
}

void RotatingFile::open(const char* mode) {
  file_ = open_file(path_, mode);
  if (file_ == nullptr) {
    error_ = "cannot open " + path_.string() + ": " + std::strerror(errno);
    return;
  }
  std::error_code ec;
  const auto size = std::filesystem::file_size(path_, ec);
  size_ = ec ? 0 : static_cast<std::size_t>(size);
}

void RotatingFile::rotate() {
  std::fclose(file_);
  file_ = nullptr;
  std::error_code ec;
  if (keep_ == 0) {
    std::filesystem::remove(path_, ec);
  } else {
    std::filesystem::remove(older(keep_), ec);
    for (std::size_t k = keep_; k > 1; --k) std::filesystem::rename(older(k - 1), older(k), ec);
    std::filesystem::rename(path_, older(1), ec);
  }
  open("wb");
}

void RotatingFile::write(std::string_view text) {
  if (file_ == nullptr) return;
  if (size_ > 0 && size_ + text.size() > max_bytes_) {
    rotate();
    if (file_ == nullptr) return;
  }
  size_ += std::fwrite(text.data(), 1, text.size(), file_);
}

void RotatingFile::flush() {
  if (file_ != nullptr) std::fflush(file_);
}

}  // namespace mocaplink::io
