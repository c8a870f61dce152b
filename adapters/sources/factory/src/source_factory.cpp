#include "mocaplink/sources/source_factory.hpp"

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

#if MOCAPLINK_HAVE_SOURCE_VICON
wire::vicon::StreamMode vicon_mode(config::ViconStreamMode mode) {
  switch (mode) {
    case config::ViconStreamMode::client_pull_prefetch:
      return wire::vicon::StreamMode::client_prefetch;
    case config::ViconStreamMode::client_pull:
      return wire::vicon::StreamMode::client_pull;
    case config::ViconStreamMode::server_push:
      break;
  }
  return wire::vicon::StreamMode::server_push;
}
#endif

}  // namespace

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
  auto parsed = config::parse_source_url(url_text);
  if (!parsed) return parsed.error();
  return make_source(parsed.value());
}

std::variant<std::unique_ptr<Source>, std::string> make_source(const config::SourceUrl& url) {
  switch (url.kind) {
#if MOCAPLINK_HAVE_SOURCE_SIM
    case config::SourceKind::sim:
      return std::unique_ptr<Source>(new SimSource(url.sim, url.text));
#endif
#if MOCAPLINK_HAVE_SOURCE_REPLAY
    case config::SourceKind::replay:
      return upcast(ReplaySource::open(
          ReplayConfig{url.replay_path, url.replay_speed, url.replay_loop}, url.text));
#endif
#if MOCAPLINK_HAVE_SOURCE_VICON
    case config::SourceKind::vicon: {
      ViconSourceOptions options;
      options.target = ViconUrl{url.host, url.port, vicon_mode(url.vicon_mode)};
      return std::unique_ptr<Source>(new ViconSource(std::move(options), url.text));
    }
#endif
    default:
      break;
  }
  return std::string(config::to_string(url.kind)) +
         "://: this mocaplink was built without that source (available: " +
         join(available_source_schemes()) + ")";
}

}  // namespace mocaplink::sources
