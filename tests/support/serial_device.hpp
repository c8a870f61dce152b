// The serial device name a test writes into a link URL: the platform's own kind (libs/config
// accepts COM port names on Windows and device paths on Linux; see link_url.cpp).
#pragma once

#include <string>

namespace mocaplink::testing_support {

#ifdef _WIN32
inline const std::string kSerialDevice = "COM3";
inline const std::string kSerialUrlPrefix = "serial://COM3";
#else
inline const std::string kSerialDevice = "/dev/ttyUSB0";
inline const std::string kSerialUrlPrefix = "serial:///dev/ttyUSB0";
#endif

}  // namespace mocaplink::testing_support
