// Test helper: a pseudo-terminal pair standing in for a serial cable. Prints the slave path (what
// `mocaplink run` opens as serial:///dev/pts/N) on stdout, then relays raw bytes between the
// master side and UDP 127.0.0.1:PORT (the Node test decodes them as a byte stream). Runs until
// killed. Usage: pty_relay PORT
#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <stdlib.h>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <string>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: pty_relay PORT\n");
    return 1;
  }
  const int master = ::posix_openpt(O_RDWR | O_NOCTTY);
  if (master < 0 || ::grantpt(master) != 0 || ::unlockpt(master) != 0) {
    std::perror("pty");
    return 1;
  }
  // Keep the slave open ourselves so the master does not see EIO between the bridge's reopens.
  const std::string slave_path = ::ptsname(master);
  const int keep = ::open(slave_path.c_str(), O_RDWR | O_NOCTTY);
  termios tio{};
  if (keep >= 0 && ::tcgetattr(keep, &tio) == 0) {
    ::cfmakeraw(&tio);
    ::tcsetattr(keep, TCSANOW, &tio);
  }
  const int udp = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in peer{};
  peer.sin_family = AF_INET;
  peer.sin_port = htons(static_cast<std::uint16_t>(std::atoi(argv[1])));
  peer.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  std::printf("%s\n", slave_path.c_str());
  std::fflush(stdout);
  std::array<pollfd, 2> fds{pollfd{master, POLLIN, 0}, pollfd{udp, POLLIN, 0}};
  std::array<char, 4096> buffer{};
  sockaddr_in any{};
  socklen_t any_len = sizeof any;
  // Bind by sending an empty datagram, so the peer can reply to our port.
  ::sendto(udp, buffer.data(), 0, 0, reinterpret_cast<const sockaddr*>(&peer), sizeof peer);
  while (::poll(fds.data(), fds.size(), -1) >= 0) {
    if ((fds[0].revents & POLLIN) != 0) {
      const ssize_t n = ::read(master, buffer.data(), buffer.size());
      if (n > 0) {
        ::sendto(udp, buffer.data(), static_cast<std::size_t>(n), 0,
                 reinterpret_cast<const sockaddr*>(&peer), sizeof peer);
      }
    }
    if ((fds[1].revents & POLLIN) != 0) {
      const ssize_t n = ::recvfrom(udp, buffer.data(), buffer.size(), 0,
                                   reinterpret_cast<sockaddr*>(&any), &any_len);
      if (n > 0) (void)!::write(master, buffer.data(), static_cast<std::size_t>(n));
    }
  }
  return 0;
}
