#include "mocaplink/io/signing_store.hpp"

#ifdef _WIN32
#include <windows.h>
#else
#include <fcntl.h>
#include <unistd.h>
#endif

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

#ifdef _WIN32
/// Writes `text` to a new file (replacing one of that name) and flushes it to the disk.
std::error_code write_durably(const std::filesystem::path& path, std::string_view text) {
  const HANDLE file = ::CreateFileW(path.c_str(), GENERIC_WRITE, 0, nullptr, CREATE_ALWAYS,
                                    FILE_ATTRIBUTE_NORMAL, nullptr);
  if (file == INVALID_HANDLE_VALUE) {
    return {static_cast<int>(::GetLastError()), std::system_category()};
  }
  DWORD written = 0;
  const bool ok =
      ::WriteFile(file, text.data(), static_cast<DWORD>(text.size()), &written, nullptr) != 0 &&
      written == text.size() && ::FlushFileBuffers(file) != 0;
  const std::error_code error =
      ok ? std::error_code{}
         : std::error_code(static_cast<int>(::GetLastError()), std::system_category());
  ::CloseHandle(file);
  return error;
}
#else
/// Writes `text` to a new file (replacing one of that name, mode 0600) and fsyncs it.
std::error_code write_durably(const std::filesystem::path& path, std::string_view text) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (fd < 0) return {errno, std::generic_category()};
  std::error_code error;
  while (!text.empty() && !error) {
    const ssize_t n = ::write(fd, text.data(), text.size());
    if (n >= 0) {
      text.remove_prefix(static_cast<std::size_t>(n));
    } else if (errno != EINTR) {
      error = {errno, std::generic_category()};
    }
  }
  if (!error && ::fsync(fd) != 0) error = {errno, std::generic_category()};
  ::close(fd);
  return error;
}
#endif

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
#ifdef _WIN32
  if (const wchar_t* dir = ::_wgetenv(L"LOCALAPPDATA"); dir != nullptr && *dir != L'\0') {
    return std::filesystem::path(dir) / "mocaplink";
  }
#endif
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
  // Written and flushed under a temporary name, then renamed over the old file: otherwise a power
  // cut can leave an empty file under the final name.
  if (const auto error = write_durably(temporary, format_signing_timestamp(timestamp_10us))) {
    if (problem != nullptr) *problem = temporary.string() + ": " + error.message();
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
