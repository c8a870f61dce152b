// MAVLink ↔ JSON (docs/mavlink.md "Command line"): the golden-vector format of
// shared/mavlink/golden-vectors.json on the way in, one JSON object per frame on the way out.
// Field values: float32 as the shortest text that reads back to the same float, or "NaN",
// "Infinity", "-Infinity", "-0"; 64-bit integers as decimal strings (JSON numbers lose precision
// beyond 2^53); char[N] as strings (NUL-padded on the wire).
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "mocaplink/mavlink/frame.hpp"
#include "mocaplink/mavlink/messages.hpp"
#include "mocaplink/mavlink/signing.hpp"

namespace mocaplink::mavlink_json {

/// Input that is not a golden vector; what() names the place first ("vectors[2].fields.x: ...").
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The typed message of a golden-vector object {"msg": NAME, "fields": {...}}: absent fields are
/// 0; a field the message does not have, a value of the wrong type or out of range is an
/// InputError naming `where`.
[[nodiscard]] mavlink::Message message_from_json(const nlohmann::json& vector,
                                                 const std::string& where);

/// One vector, encoded.
struct EncodedVector {
  std::string id;  ///< the vector's "id", or the message name in lower case
  mavlink::Frame frame;
};

/// Encodes every vector of a golden-vector document: one object, or {"key_hex": ..., "vectors":
/// [...]}. Per vector: "seq" (default 0), "sysid" and "compid" (default 1), and an optional
/// "sign": {"link_id", "timestamp"} signed with the document's "key_hex". Throws InputError.
[[nodiscard]] std::vector<EncodedVector> encode_vectors(const nlohmann::json& document);

/// encode_vectors of a document's text ("invalid JSON: ..." when it does not parse).
[[nodiscard]] std::vector<EncodedVector> encode_vectors_text(std::string_view document_text);

/// One frame as one JSON object and a newline: header fields, "fields" (null and a hex "payload"
/// for an unknown message id), and for a signed frame "link_id", "sig_timestamp", "signature"
/// and "signature_valid" (checked with `key`; false without one).
[[nodiscard]] std::string frame_to_json(const mavlink::FrameView& frame,
                                        const mavlink::SigningKey* key);

}  // namespace mocaplink::mavlink_json
