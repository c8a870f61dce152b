#include "mocaplink/io/signing_store.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <charconv>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <system_error>

#include "mocaplink/mavlink/signing.hpp"

namespace mocaplink::io {
namespace {

constexpr std::string_view kMagic = "mocaplink-signing-timestamp 1 ";

std::string errno_text(int error) {
  return std::error_code(error, std::generic_category()).message();
}

bool write_all(int fd, std::string_view text) {
  while (!text.empty()) {
    const ssize_t n = ::write(fd, text.data(), text.size());
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    text.remove_prefix(static_cast<std::size_t>(n));
  }
  return true;
}

}  // namespace

std::string format_signing_timestamp(std::uint64_t timestamp_10us) {
  return std::string(kMagic) + std::to_string(timestamp_10us) + "\n";
}

std::optional<std::uint64_t> parse_signing_timestamp(std::string_view text) {
  if (text.size() > kMaxSigningFileBytes || !text.starts_with(kMagic)) return std::nullopt;
  text.remove_prefix(kMagic.size());
  if (text.ends_with('\n')) text.remove_suffix(1);
  if (text.empty() || text.size() > 20) return std::nullopt;
  for (const char c : text) {
    if (c < '0' || c > '9') return std::nullopt;
  }
  std::uint64_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc{} || end != text.data() + text.size()) return std::nullopt;
  if (value > mavlink::kMaxSigningTimestamp) return std::nullopt;
  return value;
}

std::filesystem::path default_state_dir() {
  if (const char* dir = std::getenv("MOCAPLINK_STATE_DIR"); dir != nullptr && *dir != '\0') {
    return dir;
  }
  if (const char* dir = std::getenv("STATE_DIRECTORY"); dir != nullptr && *dir != '\0') {
    // systemd may pass several directories separated by ':'; the first is ours.
    const std::string_view dirs{dir};
    return std::filesystem::path(std::string(dirs.substr(0, dirs.find(':'))));
  }
  if (const char* dir = std::getenv("XDG_STATE_HOME"); dir != nullptr && *dir != '\0') {
    return std::filesystem::path(dir) / "mocaplink";
  }
  if (const char* home = std::getenv("HOME"); home != nullptr && *home != '\0') {
    return std::filesystem::path(home) / ".local" / "state" / "mocaplink";
  }
  return ".mocaplink-state";
}

std::filesystem::path SigningStore::path_for(std::string_view vehicle) const {
  return dir_ / (std::string(vehicle) + ".signing");
}

std::optional<std::uint64_t> SigningStore::load(std::string_view vehicle,
                                                std::string* problem) const {
  const auto path = path_for(vehicle);
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::array<char, kMaxSigningFileBytes + 1> buffer{};
  in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
  const auto n = static_cast<std::size_t>(in.gcount());
  auto value = parse_signing_timestamp(std::string_view(buffer.data(), n));
  if (!value && problem != nullptr) {
    *problem = path.string() + ": not a mocaplink signing timestamp file; ignored";
  }
  return value;
}

bool SigningStore::save(std::string_view vehicle, std::uint64_t timestamp_10us,
                        std::string* problem) const {
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  if (ec) {
    if (problem != nullptr) *problem = dir_.string() + ": " + ec.message();
    return false;
  }
  const auto path = path_for(vehicle);
  auto temporary = path;
  temporary += ".tmp";
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (fd < 0) {
    if (problem != nullptr) *problem = temporary.string() + ": " + errno_text(errno);
    return false;
  }
  const bool written = write_all(fd, format_signing_timestamp(timestamp_10us));
  const int write_error = errno;
  // fsync before rename: otherwise a power cut can leave an empty file under the final name.
  const bool synced = written && ::fsync(fd) == 0;
  const int sync_error = errno;
  ::close(fd);
  if (!written || !synced) {
    if (problem != nullptr) {
      *problem = temporary.string() + ": " + errno_text(written ? sync_error : write_error);
    }
    std::filesystem::remove(temporary, ec);
    return false;
  }
  std::filesystem::rename(temporary, path, ec);
  if (ec) {
    if (problem != nullptr) *problem = path.string() + ": " + ec.message();
    return false;
  }
  return true;
}

}  // namespace mocaplink::io
