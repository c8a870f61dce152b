// vicon-udp:// joins the binary (descriptor.hpp): the UDP object stream receiver, and its sender
// for `mocaplink serve --protocol vicon-udp --to HOST:PORT`.
#include <memory>

#include "mocaplink/sources/vicon_udp_sender.hpp"
#include "mocaplink/sources/vicon_udp_source.hpp"

namespace mocaplink::sources {

SourceDescriptor vicon_udp_source_descriptor() {
  SourceDescriptor d = describe_source<ViconUdpOptions>(
      "vicon-udp", kViconUdpOptionKeys, &parse_vicon_udp_options,
      [](ViconUdpOptions options, std::string text) -> OpenResult {
        return std::make_unique<ViconUdpSource>(std::move(options), std::move(text));
      });
  d.make_emulator = [](const EmulatorOptions& options) -> EmulatorResult {
    auto sender = vicon_udp_sender_options(options);
    if (!sender) return sender.error();
    return std::unique_ptr<Emulator>(std::make_unique<ViconUdpSender>(std::move(sender).value()));
  };
  d.serve_port = wire::vicon_udp::kDefaultPort;
  d.emulator_option_keys = kViconUdpEmulatorKeys;
  d.emulator_sends = true;
  return d;
}

}  // namespace mocaplink::sources
