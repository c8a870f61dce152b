// How a mocap source joins the binary (docs/architecture.md, "Add a mocap source"): its folder
// adapters/sources/<name>/ defines `SourceDescriptor <name>_source_descriptor()` and calls
// mocaplink_add_source(<name> ...) in its CMakeLists.txt; the registry (adapters/sources/registry)
// is generated from those calls. Everything a command needs to know about a source is here.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "mocaplink/config/source_url.hpp"
#include "mocaplink/config/url.hpp"
#include "mocaplink/core/mocap_frame.hpp"
#include "mocaplink/sources/source.hpp"

namespace mocaplink::sources {

/// A Source ready to start, or why it cannot be made (one line).
using OpenResult = std::variant<std::unique_ptr<Source>, std::string>;

/// Where `mocaplink serve` listens (or sends to) and at which frame rate it advertises/produces
/// frames, plus the protocol's own settings (`--set KEY=VALUE`).
struct EmulatorOptions {
  std::string listen_host = "0.0.0.0";
  std::uint16_t port = 0;  ///< 0 = any free port
  double rate_hz = 100.0;
  /// `--to HOST:PORT`: where a protocol that pushes datagrams unasked sends them
  /// (SourceDescriptor::emulator_sends); empty host for the others, which never get it.
  std::string to_host;
  std::uint16_t to_port = 0;
  /// `--set KEY=VALUE` in command-line order; every key is in
  /// SourceDescriptor::emulator_option_keys and given once (serve checked). Values unchecked.
  std::vector<std::pair<std::string, std::string>> settings;
};

/// A server that speaks a mocap system's protocol to its clients (`mocaplink serve`).
class Emulator {
 public:
  /// The frame for tick 0, 1, 2, … at rate_hz, or nullopt for none this tick; server's thread.
  using FrameProvider = std::function<std::optional<core::MocapFrame>(std::uint64_t tick)>;

  virtual ~Emulator() = default;
  Emulator() = default;
  Emulator(const Emulator&) = delete;
  Emulator& operator=(const Emulator&) = delete;

  /// Binds and starts serving; `provider` may be empty (publish() only). An error as a message.
  [[nodiscard]] virtual std::optional<std::string> start(FrameProvider provider) = 0;
  /// The bound port, after a successful start().
  [[nodiscard]] virtual std::uint16_t port() const = 0;
  /// Serves `frame` as the newest one; thread-safe.
  virtual void publish(core::MocapFrame frame) = 0;
  /// Closes every connection and joins. Idempotent.
  virtual void stop() = 0;
  /// What it did, for the last line of `serve`: "N frames, N clients, …".
  [[nodiscard]] virtual std::string summary() const = 0;
};

/// An emulator ready to start, or why its settings are wrong (one line).
using EmulatorResult = std::variant<std::unique_ptr<Emulator>, std::string>;

/// One mocap source: its URL scheme and options, how to open it, and what else it offers.
struct SourceDescriptor {
  std::string_view scheme;                        ///< "vicon" for vicon://
  std::span<const std::string_view> option_keys;  ///< the ?KEY=VALUE keys its URLs accept
  /// "" when the URL is valid. Given the split URL; the registry has already checked that the
  /// scheme is this one and every query key is in option_keys.
  std::function<std::string(const config::UrlParts& url)> check;
  /// Builds (does not start) the Source; `text` is the whole URL, for display. Errors that only
  /// show when opening (a replay file that cannot be read) come back as one line.
  std::function<OpenResult(const config::UrlParts& url, std::string text)> open;
  /// Optional: configuration warnings for a valid URL, e.g. a system whose default axes differ
  /// from [mocap]'s defaults when [mocap] up is not written (SourceContext).
  std::function<std::vector<std::string>(const config::UrlParts& url,
                                         const config::SourceContext& context)>
      config_warnings;
  /// Optional: the emulator behind `mocaplink serve --protocol <scheme>`, or why `options` are
  /// wrong (one line naming the setting, e.g. "version must be 3.0, 3.1, …, got 5.0"; exit 1).
  std::function<EmulatorResult(const EmulatorOptions& options)> make_emulator;
  std::uint16_t serve_port = 0;  ///< serve's default --listen port (with make_emulator)
  /// The `--set KEY=VALUE` keys its emulator accepts (with make_emulator).
  std::span<const std::string_view> emulator_option_keys;
  /// Its emulator sends datagrams to `--to HOST:PORT` unasked (vicon-udp); serve then requires
  /// --to, since nothing is sent that the user did not ask for. Others refuse --to.
  bool emulator_sends = false;
};

/// A descriptor from a source's typed options parser and opener: `parse` validates the URL into
/// Options (the one parser, used by check and open alike), `open` makes the Source from them.
template <typename Options>
[[nodiscard]] SourceDescriptor describe_source(
    std::string_view scheme, std::span<const std::string_view> option_keys,
    config::ValueOrError<Options> (*parse)(const config::UrlParts& url),
    OpenResult (*open)(Options options, std::string text)) {
  SourceDescriptor d;
  d.scheme = scheme;
  d.option_keys = option_keys;
  d.check = [parse](const config::UrlParts& url) { return parse(url).error(); };
  d.open = [parse, open](const config::UrlParts& url, std::string text) -> OpenResult {
    auto options = parse(url);
    if (!options) return options.error();
    return open(std::move(options).value(), std::move(text));
  };
  return d;
}

}  // namespace mocaplink::sources
