#include "mocaplink/web/assets.hpp"

namespace mocaplink::web {

std::optional<Asset> find_asset(std::string_view url_path) {
  if (url_path == "/") url_path = "/index.html";
  for (const Asset& asset : embedded_assets()) {
    if (asset.path == url_path) return asset;
  }
  return std::nullopt;
}

}  // namespace mocaplink::web
