#include "mocaplink/config/config_error.hpp"

namespace mocaplink::config {

std::string to_string(const ConfigError& error) {
  std::string out = error.file;
  if (error.line > 0) {
    out += ':' + std::to_string(error.line) + ':' + std::to_string(error.column);
  }
  out += ": ";
  if (!error.key.empty()) out += error.key + ": ";
  out += error.message;
  return out;
}

}  // namespace mocaplink::config
