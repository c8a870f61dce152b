// One problem found in a configuration file or command line, located precisely enough for an
// editor to jump to it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace mocaplink::config {

/// `file` is the display name given to the parser (or "--vehicle 2", "--source", "--http" for
/// command-line options, where line and column are 0). Lines and columns are 1-based.
/// `key` is the dotted path of the offending key ("vehicle[2].rate_hz"; vehicles are numbered
/// from 1 in file order), empty for TOML syntax errors.
struct ConfigError {
  std::string file;
  std::uint32_t line = 0;
  std::uint32_t column = 0;
  std::string key;
  std::string message;
  friend bool operator==(const ConfigError&, const ConfigError&) = default;
};

/// "FILE:LINE:COL: key: message"; "FILE: key: message" when line is 0; the "key: " part is left
/// out when key is empty.
[[nodiscard]] std::string to_string(const ConfigError& error);

}  // namespace mocaplink::config
