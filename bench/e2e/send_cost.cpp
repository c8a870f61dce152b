// bench/e2e send_cost: the CPU time of one UDP send on loopback (docs/performance.md "Where the
// time goes"), in three ways a bridge could send a 245-byte datagram (an ODOMETRY frame's size)
// on a connected socket: send(); send() on a socket registered with an epoll instance for reading
// (as every vehicle link is, to hear its vehicle); sendmmsg() of one message. The receiving
// socket is read with recvmmsg between rounds and never waited on, so no wake-up is billed to the
// sender. Each way runs in rounds of 64 sends, alternated, and the medians of the per-round CPU
// time per send (CLOCK_THREAD_CPUTIME_ID) are printed.
// Usage: send_cost [--rounds 2000]
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/epoll.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace {

constexpr std::size_t kDatagram = 245;
constexpr std::size_t kPerRound = 64;

double thread_cpu_ns() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e9 + static_cast<double>(ts.tv_nsec);
}

int udp_socket() {
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  if (fd < 0) {
    std::perror("socket");
    std::exit(1);
  }
  return fd;
}

sockaddr_in bound_loopback(int fd) {
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t len = sizeof a;
  if (::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 ||
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len) != 0) {
    std::perror("bind");
    std::exit(1);
  }
  return a;
}

/// A connected sender to `to`, and its receiver drained between rounds.
struct Pair {
  int receiver = udp_socket();
  int sender = udp_socket();
  Pair() {
    int big = 8 << 20;
    (void)::setsockopt(receiver, SOL_SOCKET, SO_RCVBUF, &big, sizeof big);
    const sockaddr_in to = bound_loopback(receiver);
    if (::connect(sender, reinterpret_cast<const sockaddr*>(&to), sizeof to) != 0) {
      std::perror("connect");
      std::exit(1);
    }
  }
  void drain() const {
    std::array<std::array<char, kDatagram>, kPerRound> buffers{};
    std::array<iovec, kPerRound> iov{};
    std::array<mmsghdr, kPerRound> msgs{};
    for (std::size_t i = 0; i < kPerRound; ++i) {
      iov[i] = {buffers[i].data(), buffers[i].size()};
      msgs[i].msg_hdr.msg_iov = &iov[i];
      msgs[i].msg_hdr.msg_iovlen = 1;
    }
    while (::recvmmsg(receiver, msgs.data(), kPerRound, MSG_DONTWAIT, nullptr) > 0) {
    }
  }
};

double median(std::vector<double> xs) {
  std::sort(xs.begin(), xs.end());
  return xs[xs.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  std::size_t rounds = 2000;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::string(argv[i]) == "--rounds") rounds = std::strtoul(argv[i + 1], nullptr, 10);
  }
  if (rounds == 0) rounds = 1;
  Pair plain;
  Pair polled;
  const int ep = ::epoll_create1(0);
  epoll_event ev{};
  ev.events = EPOLLIN | EPOLLET;  // what an event loop registers to read a vehicle's replies
  ev.data.fd = polled.sender;
  if (ep < 0 || ::epoll_ctl(ep, EPOLL_CTL_ADD, polled.sender, &ev) != 0) {
    std::perror("epoll");
    return 1;
  }
  Pair batched;
  std::array<char, kDatagram> bytes{};
  iovec iov{bytes.data(), bytes.size()};
  mmsghdr one{};
  one.msg_hdr.msg_iov = &iov;
  one.msg_hdr.msg_iovlen = 1;

  std::vector<double> send_ns;
  std::vector<double> epoll_ns;
  std::vector<double> sendmmsg_ns;
  const auto round = [&](const Pair& p, bool mmsg, std::vector<double>& out) {
    const double t0 = thread_cpu_ns();
    for (std::size_t k = 0; k < kPerRound; ++k) {
      if (mmsg) {
        (void)::sendmmsg(p.sender, &one, 1, 0);
      } else {
        (void)::send(p.sender, bytes.data(), bytes.size(), 0);
      }
    }
    out.push_back((thread_cpu_ns() - t0) / kPerRound);
    p.drain();
  };
  for (std::size_t r = 0; r < rounds; ++r) {
    round(plain, false, send_ns);
    round(polled, false, epoll_ns);
    round(batched, true, sendmmsg_ns);
  }
  const double base = median(send_ns);
  std::printf("CPU per 245-byte loopback datagram, median of %zu rounds of %zu:\n", rounds,
              kPerRound);
  std::printf("  send                   %7.0f ns\n", base);
  std::printf("  send, socket in epoll  %7.0f ns  (%.2fx)\n", median(epoll_ns),
              median(epoll_ns) / base);
  std::printf("  sendmmsg of one        %7.0f ns  (%.2fx)\n", median(sendmmsg_ns),
              median(sendmmsg_ns) / base);
  ::close(ep);
  return 0;
}
