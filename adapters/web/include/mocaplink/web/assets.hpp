// The dashboard page (web/*.html, *.css, *.js, *.svg), embedded into the library at build time by
// adapters/web/embed_assets.cmake. Served by DashboardServer; no files are read at run time.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

namespace mocaplink::web {

/// One embedded file. `path` is the URL path it is served at ("/index.html"); `content_type` its
/// HTTP Content-Type. Data lives in static storage for the life of the program.
struct Asset {
  std::string_view path;
  std::string_view content_type;
  std::span<const std::uint8_t> data;
};

/// Every embedded file, sorted by path. Thread-safe (immutable).
[[nodiscard]] std::span<const Asset> embedded_assets();

/// The asset served at `url_path`; "/" maps to "/index.html". std::nullopt when there is none.
[[nodiscard]] std::optional<Asset> find_asset(std::string_view url_path);

}  // namespace mocaplink::web
