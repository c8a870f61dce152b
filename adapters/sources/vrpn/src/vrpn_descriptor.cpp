// vrpn:// joins the binary (descriptor.hpp): the VRPN tracker client, and its emulator for
// `mocaplink serve --protocol vrpn`.
#include <memory>

#include "mocaplink/sources/vrpn_server.hpp"
#include "mocaplink/sources/vrpn_source.hpp"

namespace mocaplink::sources {

SourceDescriptor vrpn_source_descriptor() {
  SourceDescriptor d = describe_source<VrpnOptions>(
      "vrpn", kVrpnOptionKeys, &parse_vrpn_options, [](VrpnOptions url, std::string text) {
        return OpenResult(std::make_unique<VrpnSource>(VrpnSourceOptions{.target = std::move(url)},
                                                       std::move(text)));
      });
  d.make_emulator = [](const EmulatorOptions& serve) -> EmulatorResult {
    return std::unique_ptr<Emulator>(std::make_unique<VrpnServer>(VrpnServerOptions{
        .listen_host = serve.listen_host, .port = serve.port, .rate_hz = serve.rate_hz}));
  };
  d.serve_port = wire::vrpn::kDefaultPort;
  return d;
}

}  // namespace mocaplink::sources
