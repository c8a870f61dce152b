// GET /api/events: server-sent events carrying the status JSON, about 10 per second.
#include <atomic>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "api_fixture.hpp"

namespace mocaplink::web::testing {
namespace {

using nlohmann::json;

// Splits an SSE byte stream into events (blank-line separated) and returns each event's data.
class EventParser {
 public:
  std::vector<json> feed(const char* data, std::size_t size) {
    buffer_.append(data, size);
    std::vector<json> events;
    for (std::size_t end; (end = buffer_.find("\n\n")) != std::string::npos;) {
      const std::string block = buffer_.substr(0, end);
      buffer_.erase(0, end + 2);
      std::string payload;
      std::size_t start = 0;
      while (start < block.size()) {
        std::size_t stop = block.find('\n', start);
        if (stop == std::string::npos) stop = block.size();
        const std::string line = block.substr(start, stop - start);
        if (line.rfind("data: ", 0) == 0) payload += line.substr(6);
        if (line.rfind("event: ", 0) == 0) names.push_back(line.substr(7));
        start = stop + 1;
      }
      events.push_back(json::parse(payload));
    }
    return events;
  }
  std::vector<std::string> names;

 private:
  std::string buffer_;
};

TEST_F(ApiTest, EventsStreamTheStatusAndShowChangesAsTheyHappen) {
  EventParser parser;
  std::vector<json> events;
  std::string content_type;
  httplib::Client patcher("127.0.0.1", server_->port());
  auto res = client_->Get(
      "/api/events",
      [&](const httplib::Response& response) {
        content_type = response.get_header_value("Content-Type");
        return true;
      },
      [&](const char* data, std::size_t size) {
        for (json& event : parser.feed(data, size)) {
          events.push_back(std::move(event));
          if (events.size() == 1) {
            // Change something between two events: a later event must show it.
            auto r = patcher.Patch("/api/vehicles/quad1", R"({"rate_hz": 7})", "application/json");
            EXPECT_TRUE(r && r->status == 200);
          }
        }
        return events.empty() || events.back()["vehicles"][0]["rate_hz"] != 7.0;
      });
  // The client cancelled the stream itself once it saw the change.
  EXPECT_EQ(content_type, "text/event-stream");
  ASSERT_GE(events.size(), 2U);
  EXPECT_DOUBLE_EQ(events.front()["vehicles"][0]["rate_hz"].get<double>(), 50.0);
  EXPECT_DOUBLE_EQ(events.back()["vehicles"][0]["rate_hz"].get<double>(), 7.0);
  for (const json& event : events) {
    EXPECT_TRUE(event.contains("station"));
    EXPECT_TRUE(event.contains("alerts"));
  }
  for (const std::string& name : parser.names) EXPECT_EQ(name, "status");
}

TEST_F(ApiTest, EventsNeedTheTokenWhenOneIsSet) {
  server_->stop();
  DashboardServerConfig config;
  config.token = "0123456789abcdef";
  start(config);
  auto refused = get("/api/events");
  ASSERT_TRUE(refused);
  EXPECT_EQ(refused->status, 401);
  int events = 0;
  EventParser parser;
  auto res = client_->Get("/api/events", {{"Authorization", "Bearer 0123456789abcdef"}},
                          [&](const char* data, std::size_t size) {
                            events += static_cast<int>(parser.feed(data, size).size());
                            return events < 2;
                          });
  EXPECT_EQ(events, 2);
}

TEST_F(ApiTest, TooManyStreamsGet503AndStopEndsOpenStreams) {
  server_->stop();
  DashboardServerConfig config;
  config.max_event_clients = 1;
  start(config);

  std::mutex mutex;
  std::condition_variable cv;
  bool streaming = false;
  std::atomic<int> received{0};
  std::thread first([&] {
    httplib::Client client("127.0.0.1", server_->port());
    client.set_read_timeout(10, 0);
    client.Get("/api/events", [&](const char*, std::size_t) {
      ++received;
      {
        std::lock_guard lock(mutex);
        streaming = true;
      }
      cv.notify_all();
      return true;  // keep going until the server ends the stream
    });
  });
  {
    std::unique_lock lock(mutex);
    cv.wait(lock, [&] { return streaming; });
  }
  auto second = get("/api/events");
  ASSERT_TRUE(second);
  EXPECT_EQ(second->status, 503);
  EXPECT_EQ(body_json(second)["error"], "too many event streams open");

  server_->stop();  // must end the open stream, or join() below hangs
  first.join();
  EXPECT_GE(received.load(), 1);
}

}  // namespace
}  // namespace mocaplink::web::testing
