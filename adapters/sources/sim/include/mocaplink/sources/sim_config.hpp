// Configuration of the simulated mocap system behind `sim://` (DESIGN.md "Source URLs").
//
// URL form: sim://[?bodies=3&rate_hz=200&noise_mm=0.3&noise_deg=0.05&seed=1&drop=0&occlude=0
//                   &occlude_s=0.5&outliers=0&outlier_m=0.5&frames=0]
// Every key is optional; an unknown key or an out-of-range value is an error naming the key.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace mocaplink::sources {

/// What the simulator generates. Defaults are the demo's (DESIGN.md `sim://` line).
struct SimConfig {
  std::size_t bodies = 3;    ///< number of bodies, named Body1..BodyN; 1..64
  double rate_hz = 200.0;    ///< frame rate; (0, 2000] (Vicon systems run up to ~2 kHz)
  double noise_mm = 0.3;     ///< white position noise, standard deviation per axis, mm; [0, 1000]
  double noise_deg = 0.05;   ///< white attitude noise, std about each body axis, degrees; [0, 90]
  std::uint64_t seed = 1;    ///< same seed + same config → bit-identical frames
  double drop = 0.0;         ///< probability that a frame is never delivered; [0, 1)
  double occlude = 0.0;      ///< fraction of time each body is occluded; [0, 1]
  double occlude_s = 0.5;    ///< occlusions last whole slots of this length, s; (0, 60]
  double outliers = 0.0;     ///< probability per body and frame of a one-frame jump; [0, 1]
  double outlier_m = 0.5;    ///< size of such a jump (random direction), m; (0, 100]
  std::uint64_t frames = 0;  ///< the source finishes after this many frame numbers; 0 = never
};

/// Key/value pairs of a URL query, in order (`bodies=3&seed=2` → {{"bodies","3"},{"seed","2"}}).
using UrlQuery = std::vector<std::pair<std::string, std::string>>;

/// Builds a SimConfig from a `sim://` URL query. Errors (returned as the string alternative) name
/// the offending key and the accepted range, e.g. "sim://: unknown key 'bodys' (known: ...)".
/// Pure; thread-safe.
[[nodiscard]] std::variant<SimConfig, std::string> sim_config_from_query(const UrlQuery& query);

/// Empty string if `config` is within the documented ranges, else the first problem found.
[[nodiscard]] std::string validate_sim_config(const SimConfig& config);

}  // namespace mocaplink::sources
