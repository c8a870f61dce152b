#include "mocaplink/io/signals.hpp"

#include <csignal>
#include <system_error>
#include <utility>

#include <asio/post.hpp>

#ifdef _WIN32
#include <windows.h>

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>
#endif

namespace mocaplink::io {
namespace {

std::string_view signal_name(int signal_number) {
  switch (signal_number) {
    case SIGINT:
      return "SIGINT";
#ifdef SIGBREAK
    case SIGBREAK:
      return "Ctrl-Break";
#endif
    default:
      return "SIGTERM";
  }
}

#ifdef _WIN32
// Ctrl-C and Ctrl-Break reach asio's signal_set as SIGINT and SIGBREAK through the C runtime. A
// console close, log-off or shutdown has no signal: Windows calls the console control handler on a
// thread of its own and ends the process as soon as the handler returns. So the handler hands the
// request to the loop, waits until the StopSignals is destroyed (the owner has stopped cleanly) and
// then lets main finish (files closed, exit code) rather than return.
std::mutex console_mutex;
std::condition_variable console_stopped;
StopSignals* console_owner = nullptr;  // guarded by console_mutex
std::function<void(std::string_view)> console_deliver;

BOOL WINAPI on_console_event(DWORD event) {
  return detail::handle_console_event(event);
}
#endif

}  // namespace

#ifdef _WIN32
int detail::handle_console_event(unsigned long event, std::chrono::milliseconds exit_grace) {
  std::string_view what;
  switch (event) {
    case CTRL_CLOSE_EVENT:
      what = "console close";
      break;
    case CTRL_LOGOFF_EVENT:
      what = "log-off";
      break;
    case CTRL_SHUTDOWN_EVENT:
      what = "shutdown";
      break;
    default:
      return FALSE;  // Ctrl-C, Ctrl-Break: the C runtime's handler raises the signal
  }
  std::unique_lock lock(console_mutex);
  if (console_owner == nullptr) return FALSE;
  console_deliver(what);
  console_stopped.wait_for(lock, std::chrono::seconds(10), [] { return console_owner == nullptr; });
  lock.unlock();
  std::this_thread::sleep_for(exit_grace);
  return TRUE;
}
#endif

#ifdef _WIN32
StopSignals::StopSignals(asio::io_context& loop, Handler on_signal)
    : loop_(loop), signals_(loop, SIGINT, SIGBREAK, SIGTERM), on_signal_(std::move(on_signal)) {
  arm();
  const std::lock_guard lock(console_mutex);
  console_owner = this;
  console_deliver = [this](std::string_view what) {
    asio::post(loop_, [this, what] {
      {
        const std::lock_guard inner(console_mutex);
        if (console_owner != this) return;  // destroyed meanwhile
      }
      deliver(what);
    });
  };
  ::SetConsoleCtrlHandler(on_console_event, TRUE);
}
#else
StopSignals::StopSignals(asio::io_context& loop, Handler on_signal)
    : loop_(loop), signals_(loop, SIGINT, SIGTERM), on_signal_(std::move(on_signal)) {
  arm();
}
#endif

StopSignals::~StopSignals() {
#ifdef _WIN32
  {
    const std::lock_guard lock(console_mutex);
    console_owner = nullptr;
    console_deliver = nullptr;
  }
  console_stopped.notify_all();
  ::SetConsoleCtrlHandler(on_console_event, FALSE);
#endif
  std::error_code ignored;
  signals_.cancel(ignored);
  signals_.clear(ignored);
}

void StopSignals::arm() {
  signals_.async_wait([this](const std::error_code& error, int signal_number) {
    if (error) return;  // cancelled: the set is being destroyed
    deliver(signal_name(signal_number));
    arm();
  });
}

void StopSignals::deliver(std::string_view what) {
  ++count_;
  on_signal_(what, count_);
}

}  // namespace mocaplink::io
