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
///  sim        sim://[?bodies=3&rate_hz=200&noise_mm=0.3]  sim_bodies, sim_rate_hz, sim_noise_mm
///  replay     replay://PATH[?speed=1]                     replay_path (as written), replay_speed
///
/// The source factory (adapters/sources/factory) opens sources from `text`; the ranges here match
/// the ones it enforces, so `mocaplink check` rejects what `run` would.
struct SourceUrl {
  SourceKind kind = SourceKind::sim;
  std::string text;  ///< the URL as written, for display
  std::string host;
  std::uint16_t port = 0;
  ViconStreamMode vicon_mode = ViconStreamMode::server_push;
  std::string natnet_local_ip;
  std::string natnet_multicast = "239.255.42.99";
  std::string vrpn_tracker;
  std::uint32_t sim_bodies = 3;  ///< 1..1000 simulated bodies named Body1, Body2, ...
  double sim_rate_hz = 200.0;    ///< 0 < rate ≤ 2000
  double sim_noise_mm = 0.3;     ///< 0 ≤ noise ≤ 100, standard deviation per axis
  std::string replay_path;       ///< relative paths are relative to the working directory
  double replay_speed = 1.0;     ///< 0 < speed ≤ 100; 1 = real time
};

/// Parses a source URL. Errors name the problem and, for unknown schemes or options, the closest
/// valid spelling.
[[nodiscard]] ValueOrError<SourceUrl> parse_source_url(std::string_view text);

}  // namespace mocaplink::config
