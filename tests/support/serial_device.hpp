// The serial device name a test writes into a link URL: the platform's own kind (libs/config
// accepts COM port names on Windows and device paths on Linux; see link_url.cpp).
#pragma once

#include <string>

namespace mocaplink::testing_support {

// kLinkForms: the link forms libs/config lists in its errors, of which the serial one is the
// platform's.
#ifdef _WIN32
inline const std::string kSerialDevice = "COM3";
inline const std::string kSerialUrlPrefix = "serial://COM3";
inline const std::string kLinkForms =
    "udp://HOST:PORT[?bind=ADDR:PORT], udpin://ADDR:PORT, tcp://HOST:PORT, tcpin://ADDR:PORT "
    "serial://COMn?baud=N or ros2://[NAMESPACE]";
#else
inline const std::string kSerialDevice = "/dev/ttyUSB0";
inline const std::string kSerialUrlPrefix = "serial:///dev/ttyUSB0";
inline const std::string kLinkForms =
    "udp://HOST:PORT[?bind=ADDR:PORT], udpin://ADDR:PORT, tcp://HOST:PORT, tcpin://ADDR:PORT "
    "serial:///dev/DEVICE?baud=N or ros2://[NAMESPACE]";
#endif

}  // namespace mocaplink::testing_support
