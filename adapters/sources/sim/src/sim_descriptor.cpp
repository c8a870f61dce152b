// sim:// joins the binary (descriptor.hpp).
#include <memory>

#include "mocaplink/sources/sim_source.hpp"

namespace mocaplink::sources {

SourceDescriptor sim_source_descriptor() {
  return describe_source<SimOptions>("sim", kSimOptionKeys, &parse_sim_options,
                                     [](SimOptions options, std::string text) -> OpenResult {
                                       return std::make_unique<SimSource>(std::move(options),
                                                                          std::move(text));
                                     });
}

}  // namespace mocaplink::sources
