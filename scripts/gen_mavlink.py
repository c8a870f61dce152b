#!/usr/bin/env python3
"""Generates mocaplink's typed MAVLink messages from the committed definitions.

Input : libs/mavlink/definitions/messages.json (a copy of shared/mavlink/messages.json: wire order,
        types, units, crc_extra of the MAVLink common messages mocaplink uses).
Output: libs/mavlink/include/mocaplink/mavlink/messages.hpp  (structs, Message variant, field tables)
        libs/mavlink/include/mocaplink/mavlink/enums.hpp     (enum classes + to_string)
        libs/mavlink/src/messages_generated.cpp              (message table, variant decode)

Run `python3 scripts/gen_mavlink.py` from the repository root after changing the definitions and
commit the outputs; `python3 scripts/gen_mavlink.py --check` writes nothing and fails (with a
diff) when the committed outputs differ from what it would generate (a CTest runs it). The script checks the definitions (offsets, lengths, crc_extra computed from
the fields per "Packet Serialization", CRC_EXTRA calculation) and refuses inconsistent input.
"""
import difflib
import json
import pathlib
import re
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
DEFS = ROOT / "libs/mavlink/definitions/messages.json"
OUT_HPP = ROOT / "libs/mavlink/include/mocaplink/mavlink/messages.hpp"
OUT_ENUMS = ROOT / "libs/mavlink/include/mocaplink/mavlink/enums.hpp"
OUT_CPP = ROOT / "libs/mavlink/src/messages_generated.cpp"

CPP_TYPES = {
    "uint8_t": ("std::uint8_t", 1, "u8"),
    "uint8_t_mavlink_version": ("std::uint8_t", 1, "u8"),
    "int8_t": ("std::int8_t", 1, "i8"),
    "char": ("char", 1, "chr"),
    "uint16_t": ("std::uint16_t", 2, "u16"),
    "int16_t": ("std::int16_t", 2, "i16"),
    "uint32_t": ("std::uint32_t", 4, "u32"),
    "int32_t": ("std::int32_t", 4, "i32"),
    "float": ("float", 4, "f32"),
    "uint64_t": ("std::uint64_t", 8, "u64"),
    "int64_t": ("std::int64_t", 8, "i64"),
    "double": ("double", 8, "f64"),
}


CPP_KEYWORDS = {"static", "default", "delete", "auto", "register", "return", "switch", "case",
                "int", "char", "float", "double", "long", "short", "signed", "unsigned", "void",
                "new", "this", "true", "false", "union", "struct", "class", "enum", "const",
                "continue", "break", "do", "else", "for", "if", "while", "goto", "private",
                "public", "protected", "virtual", "operator", "template", "typename", "using",
                "namespace", "and", "or", "not", "xor", "bool", "export", "inline", "throw",
                "try", "catch", "friend", "explicit", "mutable", "volatile", "extern", "sizeof",
                "typedef", "asm", "concept", "requires"}


def crc_accumulate(data: bytes, crc: int) -> int:
    for b in data:
        tmp = b ^ (crc & 0xFF)
        tmp = (tmp ^ (tmp << 4)) & 0xFF
        crc = ((crc >> 8) ^ (tmp << 8) ^ (tmp << 3) ^ (tmp >> 4)) & 0xFFFF
    return crc


def crc_extra(name, fields):
    crc = crc_accumulate((name + " ").encode(), 0xFFFF)
    for f in fields:
        if f["extension"]:
            continue
        wire_type = "uint8_t" if f["type"] == "uint8_t_mavlink_version" else f["type"]
        crc = crc_accumulate((wire_type + " ").encode(), crc)
        crc = crc_accumulate((f["name"] + " ").encode(), crc)
        if f["array_length"] > 1:
            crc = crc_accumulate(bytes([f["array_length"]]), crc)
    return (crc & 0xFF) ^ (crc >> 8)


def camel(name: str) -> str:
    return "".join(part.capitalize() for part in name.lower().split("_"))


def enumerator(enum_name: str, value_name: str) -> str:
    base = value_name[len(enum_name) + 1:] if value_name.startswith(enum_name + "_") else value_name
    base = base.lower()
    if base[0].isdigit():
        base = enum_name.split("_")[-1].lower() + "_" + base
    if base in CPP_KEYWORDS:
        base += "_"
    return base


def check(cond, msg):
    if not cond:
        sys.exit(f"gen_mavlink: {msg}")


def main():
    defs = json.loads(DEFS.read_text())
    messages = sorted(defs["messages"].items(), key=lambda kv: kv[1]["id"])
    model = []
    for name, m in messages:
        offset = 0
        fields = []
        base_len = None
        last_size = 9
        for f in m["fields_in_wire_order"]:
            cpp, size, tag = CPP_TYPES[f["type"]]
            if f["extension"] and base_len is None:
                base_len = offset
            if not f["extension"]:
                check(size <= last_size, f"{name}.{f['name']}: base fields not sorted by size")
                last_size = size
            n = f["array_length"]
            fields.append(dict(f, cpp=cpp, size=size, tag=tag, offset=offset, n=n))
            offset += size * n
        if base_len is None:
            base_len = offset
        check(base_len == m["base_payload_length"], f"{name}: base length {base_len}")
        check(offset == m["max_payload_length"], f"{name}: max length {offset}")
        check(crc_extra(name, m["fields_in_wire_order"]) == m["crc_extra"], f"{name}: crc_extra")
        check(offset <= 255, f"{name}: payload too long")
        model.append(dict(name=name, cls=camel(name), id=m["id"], crc_extra=m["crc_extra"],
                          base_len=base_len, max_len=offset, fields=fields))
    outputs = {OUT_HPP: gen_hpp(model), OUT_CPP: gen_cpp(model), OUT_ENUMS: gen_enums(defs["enums"])}
    # Format with the repository's .clang-format (found from the output's path, so the text is
    # the same whatever the working directory) so that regenerating gives a clean diff.
    formatted = {
        path: subprocess.run(["clang-format", f"--assume-filename={path}"], input=text, text=True,
                             capture_output=True, check=True).stdout
        for path, text in outputs.items()
    }
    if "--check" in sys.argv[1:]:
        # CI (CTest GeneratedMavlinkIsUpToDate): the committed files must be what the generator
        # makes from the committed definitions.
        stale = False
        for path, text in formatted.items():
            committed = path.read_text() if path.exists() else ""
            if committed != text:
                stale = True
                rel = path.relative_to(ROOT)
                sys.stdout.writelines(difflib.unified_diff(
                    committed.splitlines(True), text.splitlines(True), f"committed/{rel}",
                    f"generated/{rel}", n=1))
        if stale:
            print("generated MAVLink code is stale: run python3 scripts/gen_mavlink.py and commit")
            sys.exit(1)
        print(f"generated MAVLink code matches {DEFS.relative_to(ROOT)}")
        return
    for path, text in formatted.items():
        path.write_text(text)


HEADER_NOTE = "// GENERATED by scripts/gen_mavlink.py from libs/mavlink/definitions/messages.json. Do not edit.\n"


def member_type(f):
    return f["cpp"] if f["n"] == 1 else f"std::array<{f['cpp']}, {f['n']}>"


def field_comment(f):
    parts = []
    if f.get("units"):
        parts.append(f"[{f['units']}]")
    if f.get("enum"):
        parts.append(f"enum {f['enum']}")
    if f["type"] == "uint8_t_mavlink_version":
        parts.append("MAVLink protocol version; the C library always sends 3")
    if f["extension"]:
        parts.append("extension (MAVLink 2 only; 0 when absent)")
    parts.append(f"wire offset {f['offset']}")
    return "; ".join(parts)


def gen_hpp(model):
    o = [HEADER_NOTE]
    o.append("""// Typed MAVLink messages (common dialect subset used by mocaplink), one struct per message.
//
// Each struct has the message's fields with their XML names and C types, in wire order (base
// fields sorted by element size, then extension fields in XML order; mavlink-wire.md §3), plus:
//   kId, kName, kCrcExtra        message id, XML name, crc_extra byte (mavlink-wire.md §2)
//   kBaseLength                  payload length without extensions (= the MAVLink 1 length)
//   kMaxLength                   payload length with all extension fields (untruncated MAVLink 2)
//   kFields                      FieldInfo per field (name, wire type, array length, offset)
//   pack(payload)                writes every field, untruncated, into a kMaxLength buffer
//   unpack(payload)              reads every field from a zero-filled kMaxLength buffer
// and a free function for_each_field(msg, f) calling f(const FieldInfo&, field&) in wire order.
// All fields default to 0 (HEARTBEAT.mavlink_version defaults to 3 as the C library sends it).
// Floats are IEEE-754 binary32 and travel bit-exactly (NaN payloads and -0.0 included). Semantics
// and units: the MAVLink message documentation; the unit of each field is in its comment.
// Thread-safety: plain values; the tables are immutable.
#pragma once

#include <array>
#include <bit>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <span>
#include <string_view>
#include <type_traits>
#include <variant>

namespace mocaplink::mavlink {

// Field IO below is memcpy of native values: MAVLink is little-endian on the wire.
static_assert(std::endian::native == std::endian::little,
              "mocaplink's MAVLink field IO assumes a little-endian host");

/// Wire type of a field element (the XML type; char arrays are strings padded with NUL).
enum class FieldType : std::uint8_t { u8, i8, chr, u16, i16, u32, i32, f32, u64, i64, f64 };

/// Name of the wire type as written in the XML ("uint8_t", "float", "char", ...).
[[nodiscard]] std::string_view to_string(FieldType type);

/// Size in bytes of one element of `type`.
[[nodiscard]] constexpr std::size_t field_size(FieldType type) {
  switch (type) {
    case FieldType::u8:
    case FieldType::i8:
    case FieldType::chr:
      return 1;
    case FieldType::u16:
    case FieldType::i16:
      return 2;
    case FieldType::u32:
    case FieldType::i32:
    case FieldType::f32:
      return 4;
    case FieldType::u64:
    case FieldType::i64:
    case FieldType::f64:
      return 8;
  }
  return 0;
}

/// One field of a message definition.
struct FieldInfo {
  std::string_view name;       ///< XML field name
  FieldType type;              ///< element type
  std::uint8_t array_length;   ///< 1 for scalars
  std::uint8_t offset;         ///< byte offset in the untruncated MAVLink 2 payload
  bool extension;              ///< after <extensions> in the XML: not in MAVLink 1, not in crc_extra
  std::string_view units;      ///< XML units ("" if none)
  std::string_view enum_name;  ///< XML enum ("" if none)
};

/// One message definition (run-time view of a struct's constants).
struct MessageInfo {
  std::uint32_t id;
  std::string_view name;
  std::uint8_t crc_extra;
  std::uint8_t base_length;
  std::uint8_t max_length;
  std::span<const FieldInfo> fields;
};

namespace detail {
// Fixed offsets inside fixed-extent spans: every access is within kMaxLength by construction
// (the generator checks the offsets), so no run-time bounds check is needed.
template <typename T, std::size_t N>
inline void store(std::span<std::uint8_t, N> p, std::size_t offset, const T& value) noexcept {
  static_assert(std::is_trivially_copyable_v<T>);
  std::memcpy(p.data() + offset, &value, sizeof(T));
}
template <typename T, std::size_t N>
inline void load(std::span<const std::uint8_t, N> p, std::size_t offset, T& value) noexcept {
  std::memcpy(&value, p.data() + offset, sizeof(T));
}
}  // namespace detail
""")
    for m in model:
        o.append(f"/// {m['name']} (#{m['id']}).")
        o.append(f"struct {m['cls']} {{")
        o.append(f"  static constexpr std::uint32_t kId = {m['id']};")
        o.append(f"  static constexpr std::string_view kName = \"{m['name']}\";")
        o.append(f"  static constexpr std::uint8_t kCrcExtra = {m['crc_extra']};")
        o.append(f"  static constexpr std::uint8_t kBaseLength = {m['base_len']};")
        o.append(f"  static constexpr std::uint8_t kMaxLength = {m['max_len']};")
        o.append(f"  static constexpr std::array<FieldInfo, {len(m['fields'])}> kFields{{{{")
        for f in m["fields"]:
            o.append(f"      {{\"{f['name']}\", FieldType::{f['tag']}, {f['n']}, {f['offset']}, "
                     f"{'true' if f['extension'] else 'false'}, \"{f.get('units', '')}\", "
                     f"\"{f.get('enum', '')}\"}},")
        o.append("  }};")
        o.append("")
        for f in m["fields"]:
            init = "{3}" if f["type"] == "uint8_t_mavlink_version" else "{}"
            o.append(f"  {member_type(f)} {f['name']}{init};  ///< {field_comment(f)}")
        o.append("")
        o.append("  /// Writes every field (untruncated) at its wire offset.")
        o.append("  void pack(std::span<std::uint8_t, kMaxLength> p) const noexcept {")
        for f in m["fields"]:
            o.append(f"    detail::store(p, {f['offset']}, {f['name']});")
        o.append("  }")
        o.append("  /// Reads every field from a full-length (zero-filled) payload.")
        o.append(f"  [[nodiscard]] static {m['cls']} unpack(std::span<const std::uint8_t, kMaxLength> p) noexcept {{")
        o.append(f"    {m['cls']} m;")
        for f in m["fields"]:
            o.append(f"    detail::load(p, {f['offset']}, m.{f['name']});")
        o.append("    return m;")
        o.append("  }")
        o.append(f"  bool operator==(const {m['cls']}&) const = default;")
        o.append("};")
        o.append("")
        o.append(f"/// Calls f(const FieldInfo&, field&) for each field of a {m['cls']} in wire order.")
        o.append("template <typename M, typename F>")
        o.append(f"  requires std::same_as<std::remove_const_t<M>, {m['cls']}>")
        o.append("void for_each_field(M& m, F&& f) {")
        for i, f in enumerate(m["fields"]):
            o.append(f"  f(M::kFields[{i}], m.{f['name']});")
        o.append("}")
        o.append("")
    o.append("/// Every typed message, in message-id order.")
    o.append("using Message = std::variant<" + ", ".join(m["cls"] for m in model) + ">;")
    o.append("")
    o.append("/// Number of known messages and the largest payload among them.")
    o.append(f"inline constexpr std::size_t kMessageCount = {len(model)};")
    o.append(f"inline constexpr std::size_t kLargestPayload = {max(m['max_len'] for m in model)};")
    o.append("""
/// The definition of message `msgid`, or nullptr if mocaplink does not know it. O(1).
[[nodiscard]] const MessageInfo* find_message_info(std::uint32_t msgid) noexcept;

/// All known message definitions, in id order.
[[nodiscard]] std::span<const MessageInfo> all_message_infos() noexcept;

/// The definition of the message held by `message`.
[[nodiscard]] const MessageInfo& message_info(const Message& message) noexcept;

/// A value-initialised message (all fields 0, HEARTBEAT.mavlink_version 3) of the given XML
/// name ("HIL_GPS") or id; nullopt if unknown.
[[nodiscard]] std::optional<Message> make_message(std::string_view name) noexcept;
[[nodiscard]] std::optional<Message> make_message(std::uint32_t msgid) noexcept;

/// Decodes a payload of message `msgid` as received (`payload.size()` = the frame's len): bytes
/// beyond the message's kMaxLength are ignored (newer dialect), missing bytes read as zero
/// (truncation, MAVLink 1 extensions). nullopt if `msgid` is unknown. Does not check a CRC.
[[nodiscard]] std::optional<Message> unpack_message(std::uint32_t msgid,
                                                    std::span<const std::uint8_t> payload) noexcept;

}  // namespace mocaplink::mavlink
""")
    return "\n".join(o)


def gen_cpp(model):
    o = [HEADER_NOTE]
    o.append("""#include <algorithm>

#include "mocaplink/mavlink/messages.hpp"

namespace mocaplink::mavlink {
namespace {

template <typename M>
constexpr MessageInfo info_of() {
  return MessageInfo{M::kId, M::kName, M::kCrcExtra, M::kBaseLength, M::kMaxLength, M::kFields};
}

constexpr std::array<MessageInfo, kMessageCount> kInfos{{""")
    for m in model:
        o.append(f"    info_of<{m['cls']}>(),")
    o.append("""}};

template <typename M>
Message unpack_as(std::span<const std::uint8_t> payload) noexcept {
  std::array<std::uint8_t, M::kMaxLength> full{};
  const std::size_t n = std::min<std::size_t>(payload.size(), M::kMaxLength);
  std::copy_n(payload.begin(), n, full.begin());
  return M::unpack(full);
}

}  // namespace

std::string_view to_string(FieldType type) {
  switch (type) {
    case FieldType::u8: return "uint8_t";
    case FieldType::i8: return "int8_t";
    case FieldType::chr: return "char";
    case FieldType::u16: return "uint16_t";
    case FieldType::i16: return "int16_t";
    case FieldType::u32: return "uint32_t";
    case FieldType::i32: return "int32_t";
    case FieldType::f32: return "float";
    case FieldType::u64: return "uint64_t";
    case FieldType::i64: return "int64_t";
    case FieldType::f64: return "double";
  }
  return "?";
}

const MessageInfo* find_message_info(std::uint32_t msgid) noexcept {
  switch (msgid) {""")
    for i, m in enumerate(model):
        o.append(f"    case {m['id']}: return &kInfos[{i}];")
    o.append("""    default: return nullptr;
  }
}

std::span<const MessageInfo> all_message_infos() noexcept { return kInfos; }

const MessageInfo& message_info(const Message& message) noexcept {
  return kInfos[message.index()];
}

""")
    o.append("std::optional<Message> make_message(std::string_view name) noexcept {")
    for m in model:
        o.append(f"  if (name == {m['cls']}::kName) return {m['cls']}{{}};")
    o.append("  return std::nullopt;")
    o.append("}")
    o.append("")
    o.append("std::optional<Message> make_message(std::uint32_t msgid) noexcept {")
    o.append("  switch (msgid) {")
    for m in model:
        o.append(f"    case {m['cls']}::kId: return {m['cls']}{{}};")
    o.append("    default: return std::nullopt;")
    o.append("  }")
    o.append("}")
    o.append("")
    o.append("""std::optional<Message> unpack_message(std::uint32_t msgid,
                                      std::span<const std::uint8_t> payload) noexcept {
  switch (msgid) {""")
    for m in model:
        o.append(f"    case {m['cls']}::kId: return unpack_as<{m['cls']}>(payload);")
    o.append("""    default: return std::nullopt;
  }
}

}  // namespace mocaplink::mavlink
""")
    return "\n".join(o)


def gen_enums(enums):
    o = [HEADER_NOTE]
    o.append("""// MAVLink enums used by the messages of messages.hpp, as enum classes with to_string (the XML
// name). Enumerators are the XML names without the enum prefix, lower case (MAV_FRAME_LOCAL_FRD ->
// MavFrame::local_frd; a name starting with a digit keeps the prefix's last word:
// GPS_FIX_TYPE_3D_FIX -> GpsFixType::type_3d_fix; C++ keywords get a trailing _:
// GPS_FIX_TYPE_STATIC -> GpsFixType::static_). Bitmask enums (…_FLAG, …_SENSOR) list single
// bits; combine their values with to_underlying. Message fields hold the raw integer.
#pragma once

#include <cstdint>
#include <string_view>
#include <type_traits>

namespace mocaplink::mavlink {

/// The integer value of an enumerator, for storing into a message field.
template <typename E>
[[nodiscard]] constexpr std::underlying_type_t<E> to_underlying(E e) noexcept {
  return static_cast<std::underlying_type_t<E>>(e);
}
""")
    for name, values in sorted(enums.items()):
        cls = camel(name)
        o.append(f"/// {name}")
        o.append(f"enum class {cls} : std::uint32_t {{")
        for v in values:
            o.append(f"  {enumerator(name, v['name'])} = {int(v['value'])}u,")
        o.append("};")
        o.append("")
        o.append(f"/// XML name of the enumerator (\"\" for a value not in the definitions).")
        o.append(f"[[nodiscard]] constexpr std::string_view to_string({cls} value) noexcept {{")
        o.append("  switch (value) {")
        seen = set()
        for v in values:
            if int(v["value"]) in seen:
                continue
            seen.add(int(v["value"]))
            o.append(f"    case {cls}::{enumerator(name, v['name'])}: return \"{v['name']}\";")
        o.append("  }")
        o.append("  return \"\";")
        o.append("}")
        o.append("")
    o.append("}  // namespace mocaplink::mavlink\n")
    return "\n".join(o)


if __name__ == "__main__":
    main()
