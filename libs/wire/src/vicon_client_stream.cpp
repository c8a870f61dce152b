#include "mocaplink/wire/vicon_client_stream.hpp"

#include <algorithm>
#include <set>
#include <unordered_map>

#include "mocaplink/wire/vicon_packet.hpp"

namespace mocaplink::wire::vicon {

namespace {

template <Item T>
[[nodiscard]] std::optional<ParseError> parse_one(const RawItem& item, std::optional<T>& slot) {
  auto parsed = parse_item<T>(item.payload, item.offset);
  if (!parsed) return parsed.error();
  slot = std::move(parsed).value();  // several items of a singular type: the last one wins
  return std::nullopt;
}

template <Item T>
[[nodiscard]] std::optional<ParseError> parse_append(const RawItem& item, std::vector<T>& list) {
  auto parsed = parse_item<T>(item.payload, item.offset);
  if (!parsed) return parsed.error();
  list.push_back(std::move(parsed).value());
  return std::nullopt;
}

bool listed(const std::set<std::uint32_t>& unchanged, ItemType t) {
  return unchanged.contains(to_u32(t));
}

}  // namespace

std::vector<std::uint32_t> client_wanted_types() {
  return {to_u32(ItemType::stream_info),      to_u32(ItemType::subject_info),
          to_u32(ItemType::frame_info),       to_u32(ItemType::global_segments),
          to_u32(ItemType::timecode),         to_u32(ItemType::latency_info),
          to_u32(ItemType::application_info), to_u32(ItemType::frame_rate_info),
          to_u32(ItemType::contents)};
}

ObjectEnums client_request(const ObjectEnums& offered) {
  const std::set<std::uint32_t> offer(offered.types.begin(), offered.types.end());
  std::set<std::uint32_t> out{to_u32(ItemType::contents)};
  for (std::uint32_t t : client_wanted_types()) {
    if (offer.contains(t)) out.insert(t);
  }
  return ObjectEnums{std::vector<std::uint32_t>(out.begin(), out.end())};
}

Result<ObjectEnums> parse_greeting(std::span<const std::byte> body) {
  auto items = split_items(body);
  if (!items) return items.error();
  for (const RawItem& item : items.value()) {
    if (item.type == to_u32(ItemType::object_enums)) {
      return parse_item<ObjectEnums>(item.payload, item.offset);
    }
  }
  return parse_error(kPacketHeaderBytes, "first packet has no ObjectEnums item");
}

Result<PacketOutcome> ClientStream::apply(std::span<const std::byte> body) {
  auto split = split_items(body);
  if (!split) return split.error();

  PacketOutcome outcome;
  StaticSet new_static;
  DynamicSet new_dynamic;
  bool static_present = false;
  bool dynamic_present = false;
  std::set<std::uint32_t> unchanged;

  // §7 step 1: parse everything first, so a malformed item leaves the cache untouched.
  for (const RawItem& item : split.value()) {
    std::optional<ParseError> err;
    const ItemClass cls = item_class(item.type);
    static_present = static_present || cls == ItemClass::static_item;
    dynamic_present = dynamic_present || cls == ItemClass::dynamic_item;
    switch (static_cast<ItemType>(item.type)) {
      case ItemType::contents: {
        auto c = parse_item<Contents>(item.payload, item.offset);
        if (!c) return c.error();
        unchanged.insert(c.value().unchanged.begin(), c.value().unchanged.end());
        break;
      }
      case ItemType::stream_info:
        err = parse_one(item, new_static.stream_info);
        break;
      case ItemType::application_info:
        err = parse_one(item, new_static.application_info);
        break;
      case ItemType::subject_info:
        err = parse_append(item, new_static.subjects);
        break;
      case ItemType::frame_info:
        err = parse_one(item, new_dynamic.frame_info);
        break;
      case ItemType::hardware_frame_info:
        err = parse_one(item, new_dynamic.hardware_frame);
        break;
      case ItemType::timecode:
        err = parse_one(item, new_dynamic.timecode);
        break;
      case ItemType::latency_info:
        err = parse_one(item, new_dynamic.latency);
        break;
      case ItemType::frame_rate_info:
        err = parse_one(item, new_dynamic.frame_rates);
        break;
      case ItemType::global_segments:
        err = parse_append(item, new_dynamic.global_segments);
        break;
      case ItemType::ping: {
        auto p = parse_item<Ping>(item.payload, item.offset);
        if (!p) return p.error();
        outcome.ping_ids.push_back(p.value().ping_id);
        break;
      }
      case ItemType::keep_alive:
        ++outcome.keep_alives;
        break;
      default:
        // Items we did not ask for (or do not know) are skipped, as the SDK does (§3); they
        // still count for static/dynamic presence above.
        ++outcome.unknown_items;
        break;
    }
    if (err) return *err;
  }

  // §7 step 2: copy "unchanged" types forward into the new sets.
  if (static_present) {
    if (listed(unchanged, ItemType::stream_info)) new_static.stream_info = static_.stream_info;
    if (listed(unchanged, ItemType::application_info)) {
      new_static.application_info = static_.application_info;
    }
    if (listed(unchanged, ItemType::subject_info)) new_static.subjects = static_.subjects;
    static_ = std::move(new_static);  // step 3 (step 4: no static item → keep the old set)
  }
  if (!dynamic_present) return outcome;
  if (listed(unchanged, ItemType::frame_info)) new_dynamic.frame_info = dynamic_.frame_info;
  if (listed(unchanged, ItemType::hardware_frame_info)) {
    new_dynamic.hardware_frame = dynamic_.hardware_frame;
  }
  if (listed(unchanged, ItemType::timecode)) new_dynamic.timecode = dynamic_.timecode;
  if (listed(unchanged, ItemType::latency_info)) new_dynamic.latency = dynamic_.latency;
  if (listed(unchanged, ItemType::frame_rate_info)) new_dynamic.frame_rates = dynamic_.frame_rates;
  if (listed(unchanged, ItemType::global_segments)) {
    new_dynamic.global_segments = dynamic_.global_segments;
  }
  dynamic_ = std::move(new_dynamic);  // step 5

  if (!dynamic_.frame_info) {
    outcome.frame_dropped_reason = "frame packet without FrameInfo";
  } else if (dynamic_.frame_info->frame_id == kInvalidFrameId) {
    outcome.frame_dropped_reason = "FrameInfo carries the reserved id 0xFFFFFFFF";
  } else {
    outcome.frame = decode();
  }
  return outcome;
}

void ClientStream::reset() {
  static_ = StaticSet{};
  dynamic_ = DynamicSet{};
}

DecodedFrame ClientStream::decode() const {
  DecodedFrame f;
  f.frame_id = dynamic_.frame_info ? dynamic_.frame_info->frame_id : 0;
  if (static_.stream_info && static_.stream_info->frame_period_ticks > 0) {
    f.frame_period_ticks = static_.stream_info->frame_period_ticks;
  }
  f.y_up = static_.application_info && static_.application_info->axis_orientation == 1;
  f.latency = dynamic_.latency;
  f.timecode = dynamic_.timecode;
  if (dynamic_.hardware_frame) f.hardware_frame = dynamic_.hardware_frame->hardware_frame;
  if (dynamic_.frame_rates) f.frame_rates_hz = dynamic_.frame_rates->rates_hz;

  // Index the per-subject pose items once (a hostile packet may hold many thousands of subjects).
  std::unordered_map<std::uint32_t, const GlobalSegments*> poses_by_subject;
  for (const GlobalSegments& g : dynamic_.global_segments)
    poses_by_subject.emplace(g.subject_id, &g);

  std::set<std::string> seen;
  for (const SubjectInfo& info : static_.subjects) {
    // The SDK looks subjects up by name, first match (§9.1): later duplicates are unreachable.
    if (!seen.insert(info.name).second) continue;
    SubjectSample s;
    s.name = info.name;
    const auto root = std::find_if(info.segments.begin(), info.segments.end(),
                                   [](const SegmentInfo& seg) { return seg.parent_id == 0; });
    if (root != info.segments.end()) {
      s.root_segment = root->name;
      const auto g = poses_by_subject.find(info.subject_id);
      if (g != poses_by_subject.end()) {
        const auto& segs = g->second->segments;
        const auto pose = std::find_if(segs.begin(), segs.end(), [&](const SegmentPose& p) {
          return p.segment_id == root->segment_id;
        });
        if (pose != segs.end()) {
          s.occluded = false;
          s.translation_mm = pose->translation_mm;
          s.rotation = pose->rotation;
        }
      }
    }
    f.subjects.push_back(std::move(s));
  }
  return f;
}

}  // namespace mocaplink::wire::vicon
