#include "mocaplink/sources/registry.hpp"

#include <utility>
#include <variant>

namespace mocaplink::sources {
namespace {

/// A URL split and matched to its source, or the reason it cannot be.
struct Resolved {
  const SourceDescriptor* source = nullptr;
  config::UrlParts parts;
  std::string error;
};

}  // namespace

SourceRegistry::SourceRegistry(std::vector<SourceDescriptor> sources)
    : sources_(std::move(sources)) {}

const SourceDescriptor* SourceRegistry::find(std::string_view scheme) const {
  for (const auto& s : sources_) {
    if (s.scheme == scheme) return &s;
  }
  return nullptr;
}

std::vector<std::string_view> SourceRegistry::schemes() const {
  std::vector<std::string_view> out;
  for (const auto& s : sources_) out.push_back(s.scheme);
  return out;
}

std::vector<std::string_view> SourceRegistry::servable() const {
  std::vector<std::string_view> out;
  for (const auto& s : sources_) {
    if (s.make_emulator) out.push_back(s.scheme);
  }
  return out;
}

namespace {

Resolved resolve(const SourceRegistry& registry, std::string_view url) {
  Resolved r;
  const auto schemes = registry.schemes();
  auto parts = config::split_url(url);
  if (!parts) {
    r.error = url.find("://") == std::string_view::npos
                  ? config::quote(url) +
                        " is not a source URL; expected SCHEME://..., where SCHEME is one of " +
                        config::join_names(schemes)
                  : parts.error();
    return r;
  }
  r.parts = std::move(parts).value();
  r.source = registry.find(r.parts.scheme);
  if (r.source == nullptr) {
    r.error = "unknown source scheme " + config::quote(r.parts.scheme) +
              config::suggest(r.parts.scheme, schemes) +
              " (one of: " + config::join_names(schemes) + ")";
    return r;
  }
  const std::string what = std::string(r.source->scheme) + "://";
  r.error = config::check_query_keys(r.parts, r.source->option_keys, what);
  if (r.error.empty()) r.error = r.source->check(r.parts);
  return r;
}

}  // namespace

config::SourceCheck SourceRegistry::check(std::string_view url,
                                          const config::SourceContext& context) const {
  Resolved r = resolve(*this, url);
  config::SourceCheck out;
  out.error = std::move(r.error);
  if (out.error.empty() && r.source->config_warnings) {
    out.warnings = r.source->config_warnings(r.parts, context);
  }
  return out;
}

OpenResult SourceRegistry::open(std::string_view url) const {
  Resolved r = resolve(*this, url);
  if (!r.error.empty()) return std::move(r.error);
  return r.source->open(r.parts, std::string(url));
}

config::SourceValidator SourceRegistry::validator() const {
  return [registry = *this](std::string_view url, const config::SourceContext& context) {
    return registry.check(url, context);
  };
}

}  // namespace mocaplink::sources
