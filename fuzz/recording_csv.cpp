// Fuzz target for the recording CSV reader (libs/wire recording_csv). Properties checked beyond
// "no crash, no sanitizer report": whatever parses, written back and parsed again, gives the same
// frames (numbers, names, tracked flags; poses to the written 6 decimals).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>
#include <variant>

#include "mocaplink/wire/recording_csv.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace mocaplink::wire;
  const std::string text(reinterpret_cast<const char*>(data), size);
  auto first = parse_recording(text);
  auto* rec = std::get_if<Recording>(&first);
  if (rec == nullptr) return 0;
  if (rec->frames.empty()) return 0;
  std::string written = format_recording_header(rec->header.source, rec->header.rate_hz);
  for (const auto& frame : rec->frames) {
    written += format_recording_frame(frame, rec->frames.front().capture_time);
  }
  auto second = parse_recording(written);
  auto* again = std::get_if<Recording>(&second);
  if (again == nullptr || again->frames.size() != rec->frames.size()) std::abort();
  for (std::size_t i = 0; i < rec->frames.size(); ++i) {
    const auto& a = rec->frames[i];
    const auto& b = again->frames[i];
    if (a.frame_number != b.frame_number || a.bodies.size() != b.bodies.size()) std::abort();
    for (std::size_t k = 0; k < a.bodies.size(); ++k) {
      if (a.bodies[k].name != b.bodies[k].name || a.bodies[k].tracked != b.bodies[k].tracked) {
        std::abort();
      }
      if (a.bodies[k].tracked) {
        const double error_m =
            (a.bodies[k].p_world_m - b.bodies[k].p_world_m).cwiseAbs().maxCoeff();
        // 6 decimals: half a unit in the last place, plus float rounding of large values.
        if (!(error_m <= 5e-7 + 1e-15 * a.bodies[k].p_world_m.cwiseAbs().maxCoeff())) std::abort();
      }
    }
  }
  return 0;
}
