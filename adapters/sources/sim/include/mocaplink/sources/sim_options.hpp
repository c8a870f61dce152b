// Options of the simulated mocap system behind `sim://` (DESIGN.md "Source URLs",
// docs/sources.md "sim://").
//
// URL form: sim://[?bodies=3&rate_hz=200&noise_mm=0.3&noise_deg=0.05&seed=1&drop=0&occlude=0
//                   &occlude_s=0.5&outliers=0&outlier_m=0.5&frames=0&churn_s=0]
// Every key is optional; parse_sim_options reports an unknown key or an out-of-range value.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include "mocaplink/config/url.hpp"

namespace mocaplink::sources {

/// What the built-in simulator generates (defaults are the demo's).
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
  /// The last body leaves the frame (is not listed at all, as when it is removed from the mocap
  /// system's model list) for churn_s seconds every 2 × churn_s, from t = churn_s on; 0 = never.
  /// [0, 3600]. Emulators serve this as bodies disappearing and reappearing (model changes).
  double churn_s = 0.0;
};

/// The `sim://` query keys.
inline constexpr std::array<std::string_view, 12> kSimOptionKeys = {
    "bodies",  "rate_hz",   "noise_mm", "noise_deg", "seed",   "drop",
    "occlude", "occlude_s", "outliers", "outlier_m", "frames", "churn_s"};

/// A split `sim://` URL (query keys already checked against kSimOptionKeys) → its options.
[[nodiscard]] config::ValueOrError<SimOptions> parse_sim_options(const config::UrlParts& url);

/// Empty string if `options` are within the documented ranges (SimOptions), else the first
/// problem found: a guard for options built in code (tests); URLs are checked when parsed.
[[nodiscard]] std::string validate_sim_options(const SimOptions& options);

}  // namespace mocaplink::sources
