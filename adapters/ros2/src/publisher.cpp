// The publishing thread: frames in, ROS messages out (publisher.hpp).
#include "mocaplink/ros2/publisher.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <thread>
#include <unordered_map>

#include <spdlog/spdlog.h>

#include "dds.hpp"
#include "mocaplink/io/clock.hpp"
#include "mocaplink/wire/ros2_messages.hpp"

namespace mocaplink::ros2 {
namespace {

/// Frames waiting for the publishing thread: ~0.25 s at 240 Hz. A thread further behind drops
/// the oldest (its poses are stale by then; the newest is worth most).
constexpr std::size_t kQueueFrames = 64;
/// Keep-last depths: a small N for pose and odom (rclcpp's default QoS keeps 10), tf2's 100.
constexpr std::uint32_t kBodyDepth = 10;
constexpr std::uint32_t kTfDepth = 100;
/// The largest pose / odom sample: 84 / 720 bytes with "world" and a short child frame, plus the
/// longest names config allows.
constexpr std::uint32_t kBodySampleBytes = 2048;
/// One TFMessage carries every body of a frame: about 100 bytes each.
constexpr std::uint32_t kTfSampleBytes = 256 * 1024;

struct Topic {
  std::string name;  // ROS name
  std::string type;  // ROS type ("geometry_msgs/msg/PoseStamped")
  std::unique_ptr<detail::Writer> writer;
  std::atomic<std::uint32_t> subscribers{0};
  std::uint64_t published = 0;  // guarded by the status mutex
};

struct Body {
  std::string token;  // "" when the body is not published (no name left, or a clash)
  Topic* pose = nullptr;
  Topic* odom = nullptr;
};

class DdsPublisher final : public Publisher {
 public:
  explicit DdsPublisher(const Ros2Options& options)
      : options_(options), settings_(options_.settings) {
    status_.domain_id = options.domain_id;
    status_.network_interface = settings_.network_interface;
    status_.implementation = detail::dds_implementation();
    std::string error;
    participant_ = detail::shared_participant(
        detail::ParticipantSettings{options.domain_id, settings_.network_interface, "mocaplink"},
        error);
    if (!participant_) {
      status_.error = error;
      spdlog::error("ros2: no DDS participant, nothing is published: {}", error);
      return;
    }
    status_.running = true;
    spdlog::info("ros2: DDS participant up ({}), domain {}, interface {}", status_.implementation,
                 options.domain_id, settings_.network_interface);
    if (settings_.tf) tf_ = make_topic("/tf", "tf2_msgs", "TFMessage", kTfDepth, kTfSampleBytes);
    thread_ = std::thread([this] { run(); });
  }

  ~DdsPublisher() override {
    {
      const std::lock_guard lock(queue_mutex_);
      stopping_ = true;
    }
    wake_.notify_one();
    if (thread_.joinable()) thread_.join();
    bodies_.clear();
    topics_.clear();  // writers before the participant
    participant_.reset();
  }

  void publish(FrameUpdate frame) override {
    if (!status_running() || frame.bodies.empty()) return;
    {
      const std::lock_guard lock(queue_mutex_);
      if (queue_.size() >= kQueueFrames) {
        queue_.pop_front();
        dropped_.fetch_add(1, std::memory_order_relaxed);
      }
      queue_.push_back(std::move(frame));
    }
    wake_.notify_one();
  }

  [[nodiscard]] Ros2Status status() const override {
    const std::lock_guard lock(status_mutex_);
    Ros2Status s = status_;
    s.frames_dropped = dropped_.load(std::memory_order_relaxed);
    for (const auto& t : topics_) {
      s.topics.push_back({t->name, t->type, t->subscribers.load(), t->published});
    }
    return s;
  }

 private:
  [[nodiscard]] bool status_running() const { return participant_ != nullptr; }

  Topic* make_topic(const std::string& name, std::string_view package, std::string_view type,
                    std::uint32_t depth, std::uint32_t max_bytes) {
    auto topic = std::make_unique<Topic>();
    topic->name = name;
    topic->type = std::string(package) + "/msg/" + std::string(type);
    Topic* t = topic.get();
    detail::WriterSettings ws;
    ws.topic = "rt" + name;  // ROS /a/b is DDS rt/a/b (ros2-dds.md §1)
    ws.type = std::string(package) + "::msg::dds_::" + std::string(type) + "_";
    ws.depth = depth;
    ws.max_sample_bytes = max_bytes;
    ws.on_matched = [t](std::uint32_t count) {
      const std::uint32_t before = t->subscribers.exchange(count);
      if (count > before) {
        spdlog::info("ros2: {}: a subscriber matched ({} now)", t->name, count);
      } else if (count < before) {
        spdlog::info("ros2: {}: a subscriber left ({} now)", t->name, count);
      }
    };
    std::string error;
    t->writer = participant_->make_writer(ws, error);
    const std::lock_guard lock(status_mutex_);
    if (!t->writer) {
      status_.error = "cannot publish " + name + ": " + error;
      spdlog::error("ros2: {}", status_.error);
    }
    topics_.push_back(std::move(topic));
    return t;
  }

  /// The body's topics, made the first time its name is seen.
  Body& body(const std::string& name) {
    if (const auto it = bodies_.find(name); it != bodies_.end()) return it->second;
    Body& b = bodies_[name];
    const std::string token = core::ros_name_token(name);
    if (token.empty()) {
      spdlog::warn("ros2: body \"{}\" has no letter or digit to make a ROS name of: not published",
                   name);
      const std::lock_guard lock(status_mutex_);
      status_.unnamed.push_back(name);
      return b;
    }
    if (const auto owner = tokens_.find(token); owner != tokens_.end()) {
      spdlog::warn(
          "ros2: body \"{}\" would be published as \"{}\", which is body \"{}\"'s: not "
          "published (rename one in the mocap system)",
          name, token, owner->second);
      const std::lock_guard lock(status_mutex_);
      status_.clashes.push_back(name + " (as " + token + ")");
      return b;
    }
    tokens_.emplace(token, name);
    b.token = token;
    if (settings_.pose) {
      b.pose = make_topic(core::ros_body_topic(settings_.ns, token, "pose"), "geometry_msgs",
                          "PoseStamped", kBodyDepth, kBodySampleBytes);
    }
    if (settings_.odom) {
      b.odom = make_topic(core::ros_body_topic(settings_.ns, token, "odom"), "nav_msgs", "Odometry",
                          kBodyDepth, kBodySampleBytes);
    }
    if (token != name) {
      spdlog::info("ros2: body \"{}\" is published as \"{}\" (ROS names)", name, token);
    }
    return b;
  }

  void write(Topic* topic, std::uint64_t& errors) {
    if (topic == nullptr || !topic->writer) return;
    if (topic->writer->write(buffer_)) {
      const std::lock_guard lock(status_mutex_);
      ++topic->published;
    } else {
      ++errors;
    }
  }

  void send(const FrameUpdate& frame) {
    // The capture time on the wall clock (ROS time), the clocks' offset taken now (io/clock.hpp).
    const wire::RosStamp stamp = wire::ros_stamp_from_unix_ns(io::unix_ns_of(frame.capture));
    std::uint64_t errors = 0;
    transforms_.clear();
    for (const BodyUpdate& update : frame.bodies) {
      if (!update.estimate.pose_valid()) continue;  // the Bridge gives only fresh poses
      Body& b = body(update.name);
      if (b.token.empty()) continue;
      const core::RosBodyState state =
          core::ros_body_state(update.estimate, settings_.axes, options_.world, update.axes);
      if (b.pose != nullptr) {
        wire::encode_pose_stamped(stamp, settings_.frame_id, state, buffer_);
        write(b.pose, errors);
      }
      if (b.odom != nullptr) {
        wire::encode_odometry(stamp, settings_.frame_id, b.token, state, buffer_);
        write(b.odom, errors);
      }
      if (tf_ != nullptr) {
        transforms_.push_back(
            {stamp, settings_.frame_id, b.token, state.position_m, state.orientation});
      }
    }
    if (tf_ != nullptr && !transforms_.empty()) {
      wire::encode_tf_message(transforms_, buffer_);
      write(tf_, errors);
    }
    const std::lock_guard lock(status_mutex_);
    ++status_.frames_published;
    status_.write_errors += errors;
  }

  void run() {
    std::vector<FrameUpdate> batch;
    for (;;) {
      {
        std::unique_lock lock(queue_mutex_);
        wake_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
        if (stopping_) return;
        batch.assign(std::make_move_iterator(queue_.begin()),
                     std::make_move_iterator(queue_.end()));
        queue_.clear();
      }
      for (const FrameUpdate& frame : batch) send(frame);
    }
  }

  const Ros2Options options_;
  const config::Ros2Settings& settings_;              // options_.settings
  std::shared_ptr<detail::Participant> participant_;  // the process's (dds.hpp)
  // The publishing thread's own (topics_ also read by status() under status_mutex_).
  std::vector<std::unique_ptr<Topic>> topics_;
  std::unordered_map<std::string, Body> bodies_;         // by mocap name
  std::unordered_map<std::string, std::string> tokens_;  // ROS token → mocap name
  Topic* tf_ = nullptr;
  std::vector<std::uint8_t> buffer_;
  std::vector<wire::RosTransform> transforms_;
  mutable std::mutex status_mutex_;
  Ros2Status status_;  // guarded by status_mutex_ (its topics are built in status())
  std::mutex queue_mutex_;
  std::condition_variable wake_;
  std::deque<FrameUpdate> queue_;  // guarded by queue_mutex_
  bool stopping_ = false;          // guarded by queue_mutex_
  std::atomic<std::uint64_t> dropped_{0};
  std::thread thread_;
};

}  // namespace

bool available() {
  return detail::dds_available();
}

std::string implementation() {
  return detail::dds_implementation();
}

std::unique_ptr<Publisher> start_publisher(const Ros2Options& options) {
  return std::make_unique<DdsPublisher>(options);
}

}  // namespace mocaplink::ros2
