#include "mocaplink/config/source_url.hpp"

#include "mocaplink/config/url.hpp"
#include "text_util.hpp"

namespace mocaplink::config {

ValueOrError<SourceUrl> parse_source_url(std::string_view text) {
  auto parts = split_url(text);
  if (!parts) {
    if (text.find("://") == std::string_view::npos) {
      return ValueOrError<SourceUrl>::failure(detail::quoted(text) +
                                              " is not a source URL; expected SCHEME://...");
    }
    return ValueOrError<SourceUrl>::failure(parts.error());
  }
  return SourceUrl{std::string(text), std::string(parts.value().scheme)};
}

}  // namespace mocaplink::config
