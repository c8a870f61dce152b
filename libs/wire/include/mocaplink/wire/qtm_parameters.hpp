// The XML answer to `GetParameters General 6D` (qtm-rt.md §5): the 6DOF body names in both
// formats (≤ 1.20 with <Bodies> and <Euler>; ≥ 1.21 without the count, <Enabled> from 1.24) and
// the General frequency; and the same XML written for the emulator. The parser is a small
// bounded XML reader of our own (no dependency): elements, attributes, text, the five named and
// numeric character references, comments, processing instructions, CDATA, DOCTYPE skipped; at
// most kMaxXmlDepth nested elements; memory proportional to the input. Unknown elements are
// ignored wherever they are. Pure; thread-safe.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mocaplink/wire/qtm_protocol.hpp"

namespace mocaplink::wire::qtm {

inline constexpr std::size_t kMaxXmlDepth = 64;

struct BodyParameters {
  std::string name;
  bool enabled = true;  ///< <Enabled> (≥ 1.24); true when absent
  /// Data_origin / Data_orientation text "0" (global) or absent. False: QTM re-expresses this
  /// body relative to another body or a custom frame (§5.2; codes unverified).
  bool global = true;
};

struct Parameters {
  std::string root;                            ///< e.g. "QTM_Parameters_Ver_1.25"
  bool has_6d = false;                         ///< a <The_6D> element was present
  std::vector<BodyParameters> bodies;          ///< in <Body> order = the data index
  std::optional<std::size_t> declared_bodies;  ///< <Bodies>N</Bodies> (≤ 1.20)
  std::array<std::string, 3> euler_names;      ///< <Euler> (≤ 1.20) or General EulerAngles
  std::optional<double> frequency_hz;          ///< General <Frequency>
  /// The first name given to more than one body ("" when all differ; §5.3: a configuration error).
  [[nodiscard]] std::string duplicate_name() const;
};

/// Parses a parameters answer (the XML packet's text). Errors: not well-formed XML (unclosed or
/// mismatched elements, bad references, deeper than kMaxXmlDepth), a <Bodies> count different
/// from the number of <Body> elements, a <Body> without <Name>.
[[nodiscard]] Result<Parameters> parse_parameters(std::string_view xml);

/// What the emulator answers for `GetParameters`: sections General and/or The_6D for `names`, in
/// the format of protocol 1.`minor` (≤ 20: <Bodies>, <Euler>; ≥ 21: §5.2, <Enabled> from 24).
struct ParametersRequest {
  bool general = false;
  bool six_d = false;
};
[[nodiscard]] std::string encode_parameters(std::span<const std::string> names, int minor,
                                            ParametersRequest sections, double frequency_hz);

}  // namespace mocaplink::wire::qtm
