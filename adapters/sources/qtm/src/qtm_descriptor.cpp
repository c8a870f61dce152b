// qtm:// joins the binary (descriptor.hpp): the QTM RT client, and its emulator for
// `mocaplink serve --protocol qtm`.
#include <memory>

#include "mocaplink/sources/qtm_server.hpp"
#include "mocaplink/sources/qtm_source.hpp"

namespace mocaplink::sources {

SourceDescriptor qtm_source_descriptor() {
  SourceDescriptor d = describe_source<QtmOptions>(
      "qtm", kQtmOptionKeys, &parse_qtm_options,
      [](QtmOptions target, std::string text) -> OpenResult {
        QtmSourceOptions options;
        options.target = std::move(target);
        return std::make_unique<QtmSource>(std::move(options), std::move(text));
      });
  d.make_emulator = [](const EmulatorOptions& options) -> EmulatorResult {
    auto settings = parse_qtm_emulator_settings(options.settings);
    if (!settings) return settings.error();
    QtmServerOptions server;
    server.listen_host = options.listen_host;
    server.port = options.port;
    server.rate_hz = options.rate_hz;
    server.session = settings.value().session;
    server.max_clients = settings.value().max_clients;
    return std::unique_ptr<Emulator>(std::make_unique<QtmServer>(server));
  };
  d.serve_port = wire::qtm::kDefaultPort;
  d.emulator_option_keys = kQtmEmulatorKeys;
  return d;
}

}  // namespace mocaplink::sources
