// bench/gcs_link: a serial cable between two pseudo-terminals, at a given baud rate.
//
// A pty carries bytes at memory speed; a UART carries baud/10 bytes per second (8N1) in each
// direction at once, and its driver buffers a little (Linux's serial core: one 4 KiB page per port)
// before write() blocks. This relay emulates that between pty A (mocaplink opens its slave as
// serial://) and pty B (the scripted vehicle opens its slave): per direction, a queue of at most
// CAP bytes (default 4096) that is read from the sending side only while it has room, and a line
// that completes one byte every 10/baud s, back to back while the queue holds bytes. A byte is
// handed to the receiving pty when its emulated transmission ends (frames are handed over at their
// last byte; the relay sleeps until the next frame's end, or at most 2 ms).
//
// What it cannot emulate: once its queue is full it stops reading, and the sender's writes then
// go into the pty's own kernel buffer (~64 KiB) instead of blocking at 4 KiB as a UART's would.
// So it reports, per direction, for how long the queue was full ("full_ms"): while that is 0 the
// emulation is exact.
//
// Output (stdout, one line each):
//   A <slave path of pty A>            once, then
//   B <slave path of pty B>            once; after that
//   O <time_usec> <read_ns> <done_ns> <queued>   per ODOMETRY (msgid 331) sent A -> B: its
//       time_usec field, when the relay read its last byte from pty A (≈ when the sender wrote
//       it, while the queue is not full), when its last byte left the emulated line, and the
//       bytes queued ahead of it when it was read;
//   S <now_ns> <ab_in> <ab_out> <ba_in> <ba_out> <ab_full_ns> <ba_full_ns> <ab_qmax> <ba_qmax>
//       every second, cumulative (bytes read, bytes delivered, time the queue was full, largest
//       queue), for A -> B and B -> A.
// Times are CLOCK_MONOTONIC in ns (node's process.hrtime.bigint() reads the same clock).
// Usage: gcs_uart_relay BAUD [CAP_BYTES]. Runs until SIGTERM or SIGINT.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <stdlib.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <string>
#include <vector>

namespace {

volatile sig_atomic_t g_stop = 0;

void on_signal(int /*signal*/) {
  g_stop = 1;
}

std::int64_t now_ns() {
  timespec ts{};
  ::clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

struct Pty {
  int master = -1;
  int keep = -1;  // the slave, held open so the master never sees EIO between the peer's opens
  std::string slave_path;
};

bool open_pty(Pty& pty) {
  pty.master = ::posix_openpt(O_RDWR | O_NOCTTY | O_NONBLOCK);
  if (pty.master < 0 || ::grantpt(pty.master) != 0 || ::unlockpt(pty.master) != 0) return false;
  pty.slave_path = ::ptsname(pty.master);
  pty.keep = ::open(pty.slave_path.c_str(), O_RDWR | O_NOCTTY);
  termios tio{};
  if (pty.keep < 0 || ::tcgetattr(pty.keep, &tio) != 0) return false;
  ::cfmakeraw(&tio);
  return ::tcsetattr(pty.keep, TCSANOW, &tio) == 0;
}

/// Finds MAVLink v1/v2 frame boundaries in a byte stream (no CRC check: the receivers check).
class Framer {
 public:
  struct Frame {
    std::uint64_t end_offset;  // stream offset one past the frame's last byte
    std::uint32_t msgid;
    std::uint64_t time_usec;  // first 8 payload bytes (zero-extended if truncated)
  };

  /// Feeds bytes that start at stream offset `offset`; appends completed frames to `out`.
  void feed(const std::uint8_t* data, std::size_t n, std::uint64_t offset,
            std::vector<Frame>& out) {
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint8_t byte = data[i];
      if (frame_.empty()) {
        if (byte != 0xFD && byte != 0xFE) continue;  // between frames: wait for a start marker
      }
      frame_.push_back(byte);
      if (frame_.size() == 3) {
        const std::size_t len = frame_[1];
        const bool v2 = frame_[0] == 0xFD;
        const bool signed_frame = v2 && (frame_[2] & 0x01) != 0;
        expected_ = (v2 ? 10 : 6) + len + 2 + (signed_frame ? 13 : 0);
      }
      if (frame_.size() >= 3 && frame_.size() == expected_) {
        const bool v2 = frame_[0] == 0xFD;
        const std::size_t header = v2 ? 10 : 6;
        Frame f{offset + i + 1, 0, 0};
        f.msgid = v2 ? (frame_[7] | (frame_[8] << 8) | (frame_[9] << 16)) : frame_[5];
        const std::size_t len = frame_[1];
        for (std::size_t k = 0; k < 8 && k < len; ++k) {
          f.time_usec |= static_cast<std::uint64_t>(frame_[header + k]) << (8 * k);
        }
        out.push_back(f);
        frame_.clear();
        expected_ = 0;
      }
    }
  }

 private:
  std::vector<std::uint8_t> frame_;
  std::size_t expected_ = 0;
};

/// One direction of the cable.
class Line {
 public:
  Line(int src, int dst, double byte_ns, std::size_t cap, bool report_odometry)
      : src_(src), dst_(dst), byte_ns_(byte_ns), cap_(cap), report_odometry_(report_odometry) {}

  [[nodiscard]] bool wants_read() const { return queued() < cap_; }
  [[nodiscard]] bool wants_write() const { return !to_deliver_.empty(); }
  [[nodiscard]] int src() const { return src_; }
  [[nodiscard]] int dst() const { return dst_; }

  /// Reads what the queue has room for.
  void read(std::int64_t now) {
    advance(now);
    std::array<std::uint8_t, 4096> buffer{};
    while (queued() < cap_) {
      const std::size_t room = std::min(buffer.size(), cap_ - queued());
      const ssize_t n = ::read(src_, buffer.data(), room);
      if (n <= 0) break;
      if (queue_.empty() && done_offset_ == end_offset_) {
        // The line was idle: this byte starts its transmission now (or when the last one ended).
        busy_start_ns_ = std::max(now, idle_since_ns_);
        busy_start_offset_ = end_offset_;
      }
      const std::size_t ahead = queued();
      std::vector<Framer::Frame> frames;
      framer_.feed(buffer.data(), static_cast<std::size_t>(n), end_offset_, frames);
      queue_.insert(queue_.end(), buffer.begin(), buffer.begin() + n);
      end_offset_ += static_cast<std::uint64_t>(n);
      bytes_in_ += static_cast<std::uint64_t>(n);
      for (const auto& f : frames) {
        frame_ends_.push_back(f.end_offset);
        if (report_odometry_ && f.msgid == 331) {
          odometry_.push_back({f.end_offset, f.time_usec, now, ahead});
        }
      }
      max_queued_ = std::max(max_queued_, queued());
    }
    if (queued() >= cap_ && full_since_ns_ < 0) full_since_ns_ = now;
  }

  /// Moves the bytes whose transmission has ended by `now` to the receiving side.
  void advance(std::int64_t now) {
    if (end_offset_ > done_offset_) {
      const auto elapsed = static_cast<double>(now - busy_start_ns_);
      const auto sent = static_cast<std::uint64_t>(std::max(0.0, elapsed / byte_ns_));
      const std::uint64_t done = std::min(end_offset_, busy_start_offset_ + sent);
      if (done > done_offset_) {
        const std::size_t count = done - done_offset_;
        to_deliver_.insert(to_deliver_.end(), queue_.begin(),
                           queue_.begin() + static_cast<std::ptrdiff_t>(count));
        queue_.erase(queue_.begin(), queue_.begin() + static_cast<std::ptrdiff_t>(count));
        done_offset_ = done;
        if (done_offset_ == end_offset_) idle_since_ns_ = completion_ns(end_offset_);
      }
      while (!frame_ends_.empty() && frame_ends_.front() <= done_offset_) frame_ends_.pop_front();
    }
    if (full_since_ns_ >= 0 && queued() < cap_) {
      full_ns_ += now - full_since_ns_;
      full_since_ns_ = -1;
    }
    deliver(now);
  }

  /// When the next frame end (or, without one, the queue's end) completes on the line; -1 if idle.
  [[nodiscard]] std::int64_t next_event_ns() const {
    if (end_offset_ == done_offset_ && to_deliver_.empty()) return -1;
    if (end_offset_ == done_offset_) return 0;  // waiting for the receiver to take bytes
    const std::uint64_t target = frame_ends_.empty() ? end_offset_ : frame_ends_.front();
    return completion_ns(target);
  }

  void print_stats(std::FILE* out) const {
    std::fprintf(out, " %llu %llu", static_cast<unsigned long long>(bytes_in_),
                 static_cast<unsigned long long>(bytes_out_));
  }
  [[nodiscard]] std::int64_t full_ns(std::int64_t now) const {
    return full_ns_ + (full_since_ns_ >= 0 ? now - full_since_ns_ : 0);
  }
  [[nodiscard]] std::size_t max_queued() const { return max_queued_; }

 private:
  struct Odometry {
    std::uint64_t end_offset;
    std::uint64_t time_usec;
    std::int64_t read_ns;
    std::size_t ahead;
  };

  [[nodiscard]] std::size_t queued() const { return queue_.size(); }

  [[nodiscard]] std::int64_t completion_ns(std::uint64_t offset) const {
    return busy_start_ns_ +
           static_cast<std::int64_t>(static_cast<double>(offset - busy_start_offset_) * byte_ns_);
  }

  void deliver(std::int64_t now) {
    while (!to_deliver_.empty()) {
      const std::size_t chunk = std::min<std::size_t>(to_deliver_.size(), 4096);
      std::array<std::uint8_t, 4096> buffer{};
      std::copy_n(to_deliver_.begin(), chunk, buffer.begin());
      const ssize_t n = ::write(dst_, buffer.data(), chunk);
      if (n <= 0) break;  // the receiver is not reading: keep the bytes, poll for POLLOUT
      to_deliver_.erase(to_deliver_.begin(), to_deliver_.begin() + n);
      delivered_offset_ += static_cast<std::uint64_t>(n);
      bytes_out_ += static_cast<std::uint64_t>(n);
    }
    while (!odometry_.empty() && odometry_.front().end_offset <= delivered_offset_) {
      const Odometry& o = odometry_.front();
      std::printf("O %llu %lld %lld %zu\n", static_cast<unsigned long long>(o.time_usec),
                  static_cast<long long>(o.read_ns), static_cast<long long>(now), o.ahead);
      odometry_.pop_front();
    }
  }

  int src_;
  int dst_;
  double byte_ns_;
  std::size_t cap_;
  bool report_odometry_;
  Framer framer_;
  std::deque<std::uint8_t> queue_;       // read, not yet through the line
  std::deque<std::uint8_t> to_deliver_;  // through the line, not yet taken by the receiver
  std::deque<std::uint64_t> frame_ends_;
  std::deque<Odometry> odometry_;
  std::uint64_t end_offset_ = 0;        // stream offset after the last byte read
  std::uint64_t done_offset_ = 0;       // after the last byte through the line
  std::uint64_t delivered_offset_ = 0;  // after the last byte written to the receiver
  std::int64_t busy_start_ns_ = 0;
  std::uint64_t busy_start_offset_ = 0;
  std::int64_t idle_since_ns_ = 0;
  std::int64_t full_since_ns_ = -1;
  std::int64_t full_ns_ = 0;
  std::uint64_t bytes_in_ = 0;
  std::uint64_t bytes_out_ = 0;
  std::size_t max_queued_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::fprintf(stderr, "usage: gcs_uart_relay BAUD [CAP_BYTES]\n");
    return 1;
  }
  const double baud = std::strtod(argv[1], nullptr);
  const auto cap = static_cast<std::size_t>(argc == 3 ? std::strtoul(argv[2], nullptr, 10) : 4096);
  if (baud <= 0 || cap == 0) {
    std::fprintf(stderr, "gcs_uart_relay: BAUD and CAP_BYTES must be positive\n");
    return 1;
  }
  ::setvbuf(stdout, nullptr, _IOLBF, 0);
  struct sigaction action {};
  action.sa_handler = on_signal;
  ::sigaction(SIGTERM, &action, nullptr);
  ::sigaction(SIGINT, &action, nullptr);
  ::signal(SIGPIPE, SIG_IGN);

  Pty a;
  Pty b;
  if (!open_pty(a) || !open_pty(b)) {
    std::perror("gcs_uart_relay: pty");
    return 1;
  }
  std::printf("A %s\nB %s\n", a.slave_path.c_str(), b.slave_path.c_str());
  const double byte_ns = 10.0 * 1e9 / baud;  // 8N1: start bit, 8 data bits, stop bit
  std::array<Line, 2> lines{Line(a.master, b.master, byte_ns, cap, true),
                            Line(b.master, a.master, byte_ns, cap, false)};
  std::int64_t next_stats = now_ns() + 1'000'000'000;
  while (g_stop == 0) {
    std::int64_t now = now_ns();
    std::array<pollfd, 4> fds{};
    nfds_t count = 0;
    for (auto& line : lines) {
      if (line.wants_read()) fds[count++] = pollfd{line.src(), POLLIN, 0};
      if (line.wants_write()) fds[count++] = pollfd{line.dst(), POLLOUT, 0};
    }
    std::int64_t wake = next_stats;
    for (const auto& line : lines) {
      const std::int64_t event = line.next_event_ns();
      if (event >= 0) wake = std::min(wake, std::max(event, now + 20'000));  // POLLOUT case: 20 µs
    }
    wake = std::min(wake, now + 2'000'000);
    const std::int64_t wait = std::max<std::int64_t>(0, wake - now);
    const timespec timeout{static_cast<time_t>(wait / 1'000'000'000),
                           static_cast<long>(wait % 1'000'000'000)};
    if (::ppoll(fds.data(), count, &timeout, nullptr) < 0 && errno != EINTR) {
      std::perror("gcs_uart_relay: ppoll");
      return 1;
    }
    now = now_ns();
    for (auto& line : lines) line.advance(now);
    for (nfds_t i = 0; i < count; ++i) {
      if ((fds[i].revents & POLLIN) == 0) continue;
      for (auto& line : lines) {
        if (line.src() == fds[i].fd) line.read(now);
      }
    }
    if (now >= next_stats) {
      std::printf("S %lld", static_cast<long long>(now));
      lines[0].print_stats(stdout);
      lines[1].print_stats(stdout);
      std::printf(" %lld %lld %zu %zu\n", static_cast<long long>(lines[0].full_ns(now)),
                  static_cast<long long>(lines[1].full_ns(now)), lines[0].max_queued(),
                  lines[1].max_queued());
      next_stats += 1'000'000'000;
    }
  }
  return 0;
}
