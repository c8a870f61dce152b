// Whether standard output is a terminal that understands ANSI escape sequences (a live view
// redraws in place there; piped or redirected output gets plain blocks).
#pragma once

namespace mocaplink::io {

/// Linux: stdout is a tty. Windows: stdout is a console, whose virtual-terminal processing this
/// turns on (Windows 10 and later); false when it cannot.
[[nodiscard]] bool stdout_is_ansi_terminal() noexcept;

}  // namespace mocaplink::io
