// io::make_link: each link URL kind becomes the Link class that speaks it, not started.
#include "mocaplink/io/make_link.hpp"

#include <gtest/gtest.h>

#include "mocaplink/io/link_serial.hpp"
#include "mocaplink/io/link_tcp.hpp"
#include "mocaplink/io/link_udp.hpp"
#include "serial_device.hpp"

namespace mocaplink::io {
namespace {

std::unique_ptr<Link> make(asio::io_context& loop, const char* url) {
  const auto parsed = config::parse_link_url(url);
  EXPECT_TRUE(parsed) << parsed.error();
  LinkOptions options;
  options.name = "v";
  return make_link(loop, parsed.value(), std::move(options));
}

TEST(MakeLink, EachKindGetsItsLinkClass) {
  asio::io_context loop;
  EXPECT_NE(dynamic_cast<UdpLink*>(make(loop, "udp://127.0.0.1:14540").get()), nullptr);
  EXPECT_NE(dynamic_cast<TcpLink*>(make(loop, "tcp://127.0.0.1:5760").get()), nullptr);
  EXPECT_NE(dynamic_cast<SerialLink*>(
                make(loop, (testing_support::kSerialUrlPrefix + "?baud=921600").c_str()).get()),
            nullptr);
}

}  // namespace
}  // namespace mocaplink::io
