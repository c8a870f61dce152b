// Mocap source URLs (DESIGN.md "Command line"), parsed and checked for syntax and options only;
// the source adapters connect. Every option not given is filled with its documented default, so a
// SourceUrl is complete.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "mocaplink/config/value_or_error.hpp"

namespace mocaplink::config {

enum class SourceKind { vicon, vicon_udp, natnet, vrpn, qtm, sim, replay };

/// The URL scheme: "vicon", "vicon-udp", "natnet", "vrpn", "qtm", "sim", "replay".
[[nodiscard]] const char* to_string(SourceKind kind);

/// Vicon DataStream stream modes (protocols/vicon-datastream.md §6). `?mode=push|prefetch|pull`.
enum class ViconStreamMode { server_push, client_pull_prefetch, client_pull };

/// "push", "prefetch", "pull".
[[nodiscard]] const char* to_string(ViconStreamMode mode);

/// What the built-in simulator generates (`sim://` options; defaults are the demo's).
struct SimOptions {
  std::uint32_t bodies = 3;  ///< bodies, named Body1..BodyN; 1..64
  double rate_hz = 200.0;    ///< frame rate; (0, 2000] (Vicon systems run up to ~2 kHz)
  double noise_mm = 0.3;     ///< white position noise, standard deviation per axis, mm; [0, 1000]
  double noise_deg = 0.05;   ///< white attitude noise, std about each body axis, degrees; [0, 90]
  std::uint64_t seed = 1;    ///< same seed + same options → bit-identical frames
  double drop = 0.0;         ///< probability that a frame is never delivered; [0, 1)
  double occlude = 0.0;      ///< fraction of time each body is occluded; [0, 1]
  double occlude_s = 0.5;    ///< occlusions last whole slots of this length, s; (0, 60]
  double outliers = 0.0;     ///< probability per body and frame of a one-frame jump; [0, 1]
  double outlier_m = 0.5;    ///< size of such a jump (random direction), m; (0, 100]
  std::uint64_t frames = 0;  ///< the source finishes after this many frames; 0 = never
};

/// A parsed source URL. Only the fields documented for `kind` are meaningful; the others keep
/// their defaults.
///
///  kind       URL form                                   fields
///  vicon      vicon://host[:801][?mode=push]              host, port (801), vicon_mode (push)
///  vicon_udp  vicon-udp://[bind][:51001]                  host ("" = all interfaces), port (51001)
///  natnet     natnet://server[?local=IP&multicast=GROUP]  host (no port: Motive's command port
///                                                         1510 / data port 1511), natnet_local_ip
///                                                         ("" = any), natnet_multicast
///                                                         ("239.255.42.99")
///  vrpn       vrpn://[Tracker@]host[:3883]                vrpn_tracker ("" = every tracker),
///                                                         host, port (3883)
///  qtm        qtm://host[:22223]                          host, port (22223)
///  sim        sim://[?bodies=3&rate_hz=200&...]           sim (every SimOptions key)
///  replay     replay://PATH[?speed=1&loop=0]              replay_path (as written), replay_speed,
///                                                         replay_loop
///
/// This is the one parser of source URLs: the config checker, `run`, `bodies`, `record` and
/// `serve --from` all use it (the source factory, adapters/sources/factory, opens sources from
/// the parsed URL), so `mocaplink check` accepts exactly what `run` does.
struct SourceUrl {
  SourceKind kind = SourceKind::sim;
  std::string text;  ///< the URL as written, for display
  std::string host;
  std::uint16_t port = 0;
  ViconStreamMode vicon_mode = ViconStreamMode::server_push;
  std::string natnet_local_ip;
  std::string natnet_multicast = "239.255.42.99";
  std::string vrpn_tracker;
  SimOptions sim;
  std::string replay_path;    ///< relative paths are relative to the working directory
  double replay_speed = 1.0;  ///< 0 ≤ speed ≤ 1000; 1 = real time, 0 = as fast as possible
  bool replay_loop = false;   ///< start again at the end instead of finishing
};

/// Parses a source URL. Errors name the problem and, for unknown schemes or options, the closest
/// valid spelling.
[[nodiscard]] ValueOrError<SourceUrl> parse_source_url(std::string_view text);

}  // namespace mocaplink::config
