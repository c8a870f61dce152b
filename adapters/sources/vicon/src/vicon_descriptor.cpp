// vicon:// joins the binary (descriptor.hpp): the DataStream client, and its emulator for
// `mocaplink serve --protocol vicon`.
#include <memory>

#include "mocaplink/sources/vicon_server.hpp"
#include "mocaplink/sources/vicon_source.hpp"

namespace mocaplink::sources {

SourceDescriptor vicon_source_descriptor() {
  SourceDescriptor d = describe_source<ViconOptions>(
      "vicon", kViconOptionKeys, &parse_vicon_options,
      [](ViconOptions target, std::string text) -> OpenResult {
        ViconSourceOptions options;
        options.target = std::move(target);
        return std::make_unique<ViconSource>(std::move(options), std::move(text));
      });
  d.make_emulator = [](const EmulatorOptions& options) -> EmulatorResult {
    ViconServerOptions server;
    server.listen_host = options.listen_host;
    server.port = options.port;
    server.rate_hz = options.rate_hz;
    return std::unique_ptr<Emulator>(std::make_unique<ViconServer>(server));
  };
  d.serve_port = wire::vicon::kDefaultPort;
  return d;
}

}  // namespace mocaplink::sources
