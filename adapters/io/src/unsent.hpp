// Bytes a descriptor has written that the OS has not sent yet (internal to adapters/io): the
// poses-first rule of stream links (link_stream.hpp) forwards a ground station's frame only when
// little waits there.
#pragma once

#include <cstddef>
#include <optional>

#ifdef __linux__
#include <sys/ioctl.h>
#include <termios.h>  // TIOCOUTQ, which is also SIOCOUTQ for sockets
#endif

namespace mocaplink::io::detail {

/// TIOCOUTQ on a tty or a TCP socket (Linux); nullopt where the platform cannot tell or the call
/// fails.
template <typename Handle>
[[nodiscard]] std::optional<std::size_t> unsent_bytes(Handle handle) noexcept {
#ifdef __linux__
  int n = 0;
  if (::ioctl(handle, TIOCOUTQ, &n) == 0 && n >= 0) return static_cast<std::size_t>(n);
#else
  (void)handle;
#endif
  return std::nullopt;
}

}  // namespace mocaplink::io::detail
