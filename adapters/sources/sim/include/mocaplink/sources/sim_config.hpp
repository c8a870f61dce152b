// Configuration of the simulated mocap system behind `sim://` (DESIGN.md "Source URLs").
//
// URL form: sim://[?bodies=3&rate_hz=200&noise_mm=0.3&noise_deg=0.05&seed=1&drop=0&occlude=0
//                   &occlude_s=0.5&outliers=0&outlier_m=0.5&frames=0]
// Every key is optional; config::parse_source_url reports an unknown key or an out-of-range value.
#pragma once

#include <string>

#include "mocaplink/config/source_url.hpp"

namespace mocaplink::sources {

/// What the simulator generates: the `sim://` options, parsed and range-checked by the one source
/// URL parser (config::parse_source_url).
using SimConfig = config::SimOptions;

/// Empty string if `config` is within the documented ranges (SimOptions), else the first problem
/// found: a guard for configs built in code (tests, `serve --rate`); URLs are checked when parsed.
[[nodiscard]] std::string validate_sim_config(const SimConfig& config);

}  // namespace mocaplink::sources
