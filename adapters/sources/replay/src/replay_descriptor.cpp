// replay:// joins the binary (descriptor.hpp).
#include "mocaplink/sources/replay_source.hpp"

namespace mocaplink::sources {

SourceDescriptor replay_source_descriptor() {
  return describe_source<ReplayOptions>(
      "replay", kReplayOptionKeys, &parse_replay_options,
      [](ReplayOptions options, std::string text) -> OpenResult {
        auto opened = ReplaySource::open(std::move(options), std::move(text));
        if (auto* error = std::get_if<std::string>(&opened)) return std::move(*error);
        return std::move(std::get<std::unique_ptr<ReplaySource>>(opened));
      });
}

}  // namespace mocaplink::sources
