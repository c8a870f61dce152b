// StopSignals: a stop request reaches the loop thread by name, once per request.
#include "mocaplink/io/signals.hpp"

#include <csignal>
#include <future>
#include <optional>
#include <string>

#include <gtest/gtest.h>

#ifdef _WIN32
#include <windows.h>
#endif

namespace mocaplink::io {
namespace {

TEST(StopSignals, ARaisedSignalReachesTheLoopByName) {
  asio::io_context loop;
  std::string what;
  int count = 0;
  StopSignals signals(loop, [&](std::string_view name, int n) {
    what = std::string(name);
    count = n;
    loop.stop();
  });
  std::raise(SIGINT);
  loop.run();
  EXPECT_EQ(what, "SIGINT");
  EXPECT_EQ(count, 1);
  EXPECT_EQ(signals.count(), 1);
}

#ifdef _WIN32
// A console close: Windows calls the handler on a thread of its own and ends the process when it
// returns, so it must hand the request to the loop and return only once the owner has stopped.
TEST(StopSignals, ConsoleCloseWaitsForTheCleanStop) {
  asio::io_context loop;
  std::optional<StopSignals> signals;
  std::string what;
  signals.emplace(loop, [&](std::string_view name, int) {
    what = std::string(name);
    loop.stop();
  });
  auto handler = std::async(std::launch::async, [] {
    return detail::handle_console_event(CTRL_CLOSE_EVENT, std::chrono::milliseconds(0));
  });
  auto guard = asio::make_work_guard(loop);
  loop.run();  // until the handler's request arrives
  EXPECT_EQ(what, "console close");
  EXPECT_NE(handler.wait_for(std::chrono::milliseconds(0)), std::future_status::ready)
      << "the console handler returned before the owner stopped";
  signals.reset();  // the owner's clean stop is done: now the handler may return
  EXPECT_EQ(handler.get(), TRUE);
}

TEST(StopSignals, CtrlCIsLeftToTheCRuntimeAndNothingIsHandledWithoutAnOwner) {
  EXPECT_EQ(detail::handle_console_event(CTRL_C_EVENT), FALSE);
  EXPECT_EQ(detail::handle_console_event(CTRL_CLOSE_EVENT), FALSE);  // no StopSignals alive
}
#endif

}  // namespace
}  // namespace mocaplink::io
