// Fuzz target for the signing-timestamp file parser (adapters/io signing_store). Properties beyond
// "no crash": a parsed value is ≤ 48 bits and formats back to text that parses to the same value.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "mocaplink/io/signing_store.hpp"
#include "mocaplink/mavlink/signing.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const auto value = mocaplink::io::parse_signing_timestamp(text);
  if (!value) return 0;
  if (*value > mocaplink::mavlink::kMaxSigningTimestamp) std::abort();
  if (mocaplink::io::parse_signing_timestamp(mocaplink::io::format_signing_timestamp(*value)) !=
      value) {
    std::abort();
  }
  return 0;
}
