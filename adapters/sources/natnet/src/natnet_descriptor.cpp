// natnet:// joins the binary (descriptor.hpp): the NatNet client, the reminder that Motive streams
// Y-up, and the emulator for `mocaplink serve --protocol natnet`.
#include <memory>

#include "mocaplink/sources/natnet_server.hpp"
#include "mocaplink/sources/natnet_source.hpp"

namespace mocaplink::sources {

SourceDescriptor natnet_source_descriptor() {
  SourceDescriptor d = describe_source<NatnetOptions>(
      "natnet", kNatnetOptionKeys, &parse_natnet_options,
      [](NatnetOptions target, std::string text) -> OpenResult {
        NatnetSourceOptions options;
        options.target = std::move(target);
        return std::make_unique<NatnetSource>(std::move(options), std::move(text));
      });
  d.config_warnings = [](const config::UrlParts&, const config::SourceContext& context) {
    std::vector<std::string> out;
    if (!context.up_written) {
      out.emplace_back(
          "natnet:// with [mocap] up not written: Motive streams Y-up by default, so set "
          "up = \"+y\" and body_up = \"+y\" (a rigid body created level takes Motive's axes), "
          "or set Motive's Up Axis to Z and up = \"+z\" explicitly");
    }
    return out;
  };
  d.make_emulator = [](const EmulatorOptions& options) -> EmulatorResult {
    auto server = natnet_server_options(options);
    if (auto* err = std::get_if<std::string>(&server)) return *err;
    return std::unique_ptr<Emulator>(
        std::make_unique<NatnetServer>(std::get<NatnetServerOptions>(std::move(server))));
  };
  d.serve_port = wire::natnet::kDefaultCommandPort;
  d.emulator_option_keys = kNatnetEmulatorKeys;
  return d;
}

}  // namespace mocaplink::sources
