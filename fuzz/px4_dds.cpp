// Fuzz target for the decoders of PX4's DDS samples (libs/wire px4_messages): the input is one
// sample as a DDS reader hands it over (encapsulation header first), read as both types.
#include <cstddef>
#include <cstdint>
#include <span>

#include "mocaplink/wire/px4_messages.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> sample(data, size);
  (void)mocaplink::wire::decode_px4_vehicle_odometry(sample);
  (void)mocaplink::wire::decode_px4_vehicle_status(sample);
  return 0;
}
