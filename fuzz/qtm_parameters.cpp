// Fuzz target for the QTM parameters XML reader (libs/wire qtm_parameters): any text, as the
// payload of an XML packet; what parses must encode and parse back to the same names.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "mocaplink/wire/qtm_parameters.hpp"

namespace wq = mocaplink::wire::qtm;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view xml(reinterpret_cast<const char*>(data), size);
  const auto parsed = wq::parse_parameters(xml);
  if (!parsed) return 0;
  std::vector<std::string> names;
  for (const auto& b : parsed.value().bodies) {
    // Control characters do not survive XML text (whitespace is trimmed, NUL ends the packet).
    for (const char c : b.name) {
      if (static_cast<unsigned char>(c) < 0x20) return 0;
    }
    names.push_back(b.name);
  }
  for (const int minor : {19, 25}) {
    const auto back = wq::parse_parameters(wq::encode_parameters(names, minor, {true, true}, 100));
    if (!back || back.value().bodies.size() != names.size()) std::abort();
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (back.value().bodies[i].name != names[i]) std::abort();
    }
  }
  return 0;
}
