// Source URLs → Sources (DESIGN.md "Source URLs"). The registry holds the descriptor of every
// source built in (builtin_sources(), generated from each source folder's mocaplink_add_source())
// and is the only dispatch on the scheme: `check`, `run`, `bodies`, `record` and `serve` all go
// through it, so they accept exactly the same URLs. No global state: main() builds one and the
// commands pass it on. Thread-safe once built (const).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "mocaplink/config/source_url.hpp"
#include "mocaplink/sources/descriptor.hpp"

namespace mocaplink::sources {

class SourceRegistry {
 public:
  explicit SourceRegistry(std::vector<SourceDescriptor> sources);

  /// The source for `scheme`, or nullptr.
  [[nodiscard]] const SourceDescriptor* find(std::string_view scheme) const;
  /// Every scheme, in registration order, e.g. {"replay", "sim", "vicon"}.
  [[nodiscard]] std::vector<std::string_view> schemes() const;
  /// The schemes `mocaplink serve --protocol` can emulate.
  [[nodiscard]] std::vector<std::string_view> servable() const;

  /// Validates a source URL: its shape, a scheme this binary has ("unknown source scheme …" with
  /// the available ones otherwise), its option keys ("did you mean") and the source's own rules;
  /// then the source's configuration warnings for `context`.
  [[nodiscard]] config::SourceCheck check(std::string_view url,
                                          const config::SourceContext& context = {}) const;
  /// check(), then the Source (not started). Every problem is one line, so callers can exit 1
  /// before anything runs; a network source is not probed here.
  [[nodiscard]] OpenResult open(std::string_view url) const;
  /// check() as the configuration's source validator (load_config, parse_config, …). Copies the
  /// registry, so it may outlive it.
  [[nodiscard]] config::SourceValidator validator() const;

 private:
  std::vector<SourceDescriptor> sources_;
};

/// Every source built into this binary (generated: adapters/sources/registry/CMakeLists.txt).
[[nodiscard]] SourceRegistry builtin_sources();

}  // namespace mocaplink::sources
