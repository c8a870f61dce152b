// Helpers shared by the config tests.
#pragma once

#include <string>
#include <vector>

#include "mocaplink/config/load.hpp"

namespace mocaplink::config::testing_util {

/// Every error as the user sees it ("FILE:LINE:COL: key: message").
inline std::vector<std::string> error_lines(const ConfigResult& result) {
  std::vector<std::string> out;
  for (const auto& e : result.errors) out.push_back(to_string(e));
  return out;
}

/// Every warning, formatted the same way.
inline std::vector<std::string> warning_lines(const ConfigResult& result) {
  std::vector<std::string> out;
  for (const auto& w : result.warnings) out.push_back(to_string(w));
  return out;
}

}  // namespace mocaplink::config::testing_util
