#include "mocaplink/sources/source_factory.hpp"

#include <algorithm>
#include <cctype>

#if MOCAPLINK_HAVE_SOURCE_SIM
#include "mocaplink/sources/sim_source.hpp"
#endif
#if MOCAPLINK_HAVE_SOURCE_REPLAY
#include "mocaplink/sources/replay_source.hpp"
#endif
#if MOCAPLINK_HAVE_SOURCE_VICON
#include "mocaplink/sources/vicon_source.hpp"
#endif

namespace mocaplink::sources {
namespace {

/// Every scheme of DESIGN.md, built in or not, to tell "not built" from "misspelled".
constexpr std::string_view kDesignSchemes[] = {"vicon", "vicon-udp", "natnet", "vrpn",
                                               "qtm",   "sim",       "replay"};

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& item : items) out += (out.empty() ? "" : ", ") + item;
  return out;
}

/// Moves a unique_ptr<Derived> (or an error) into the factory's result type.
template <typename Derived>
std::variant<std::unique_ptr<Source>, std::string> upcast(
    std::variant<std::unique_ptr<Derived>, std::string> made) {
  if (auto* error = std::get_if<std::string>(&made)) return std::move(*error);
  return std::unique_ptr<Source>(std::move(std::get<std::unique_ptr<Derived>>(made)));
}

}  // namespace

std::variant<SourceUrl, std::string> parse_source_url(std::string_view url) {
  const auto separator = url.find("://");
  if (separator == std::string_view::npos || separator == 0) {
    return "'" + std::string(url) + "' is not a source URL (want scheme://..., e.g. sim://)";
  }
  SourceUrl out;
  out.scheme = std::string(url.substr(0, separator));
  std::transform(out.scheme.begin(), out.scheme.end(), out.scheme.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  std::string_view tail = url.substr(separator + 3);
  const auto question = tail.find('?');
  out.rest = std::string(tail.substr(0, question));
  std::string_view query = question == std::string_view::npos ? "" : tail.substr(question + 1);
  while (!query.empty()) {
    const auto amp = query.find('&');
    const std::string_view part = query.substr(0, amp);
    query = amp == std::string_view::npos ? "" : query.substr(amp + 1);
    if (part.empty()) continue;
    const auto eq = part.find('=');
    if (eq == std::string_view::npos || eq == 0) {
      return out.scheme + "://: query part '" + std::string(part) + "' is not key=value";
    }
    out.query.emplace_back(std::string(part.substr(0, eq)), std::string(part.substr(eq + 1)));
  }
  return out;
}

std::vector<std::string> available_source_schemes() {
  std::vector<std::string> out;
#if MOCAPLINK_HAVE_SOURCE_SIM
  out.emplace_back("sim");
#endif
#if MOCAPLINK_HAVE_SOURCE_REPLAY
  out.emplace_back("replay");
#endif
#if MOCAPLINK_HAVE_SOURCE_VICON
  out.emplace_back("vicon");
#endif
  return out;
}

std::variant<std::unique_ptr<Source>, std::string> make_source(std::string_view url_text) {
  auto parsed = parse_source_url(url_text);
  if (auto* error = std::get_if<std::string>(&parsed)) return std::move(*error);
  SourceUrl& url = std::get<SourceUrl>(parsed);
  const std::string text(url_text);

#if MOCAPLINK_HAVE_SOURCE_SIM
  if (url.scheme == "sim") {
    if (!url.rest.empty() && url.rest != "/") {
      return "sim://: takes no host or path, only options (sim://?bodies=3), got '" + url.rest +
             "'";
    }
    auto config = sim_config_from_query(url.query);
    if (auto* error = std::get_if<std::string>(&config)) return std::move(*error);
    return std::unique_ptr<Source>(new SimSource(std::get<SimConfig>(config), text));
  }
#endif
#if MOCAPLINK_HAVE_SOURCE_REPLAY
  if (url.scheme == "replay") {
    auto config = replay_config_from_url(url.rest, url.query);
    if (auto* error = std::get_if<std::string>(&config)) return std::move(*error);
    return upcast(ReplaySource::open(std::get<ReplayConfig>(std::move(config)), text));
  }
#endif
#if MOCAPLINK_HAVE_SOURCE_VICON
  if (url.scheme == "vicon") return upcast(ViconSource::create(text));
#endif

  const auto available = available_source_schemes();
  if (std::find(std::begin(kDesignSchemes), std::end(kDesignSchemes), url.scheme) !=
      std::end(kDesignSchemes)) {
    return url.scheme +
           "://: this mocaplink was built without that source (available: " + join(available) + ")";
  }
  return "unknown source scheme '" + url.scheme + "://' (available: " + join(available) + ")";
}

}  // namespace mocaplink::sources
