#include "mocaplink/wire/vicon_server_session.hpp"

#include <algorithm>

#include "mocaplink/wire/vicon_packet.hpp"

namespace mocaplink::wire::vicon {

namespace {

template <Item T>
std::vector<std::byte> payload_of(const T& item) {
  std::vector<std::byte> out;
  encode_item_payload(item, out);
  return out;
}

std::vector<std::byte> single_item_packet(const auto& item) {
  PacketBuilder b;
  b.add(item);
  return b.finish();
}

template <ItemType K>
SegmentPoses<K> poses_of(const ServedSubject& s) {
  SegmentPoses<K> item;
  item.subject_id = s.subject_id;
  // Occluded: the item stays, with no segment (§9.3, spec example 3).
  if (s.tracked) item.segments.push_back(SegmentPose{1, s.translation_mm, s.rotation});
  return item;
}

}  // namespace

std::vector<std::uint32_t> server_offered_types() {
  return {to_u32(ItemType::stream_info),     to_u32(ItemType::subject_info),
          to_u32(ItemType::frame_info),      to_u32(ItemType::local_segments),
          to_u32(ItemType::global_segments), to_u32(ItemType::timecode),
          to_u32(ItemType::latency_info),    to_u32(ItemType::application_info),
          to_u32(ItemType::frame_rate_info), to_u32(ItemType::object_quality),
          to_u32(ItemType::contents)};
}

std::vector<std::byte> ServerSession::greeting() const {
  return single_item_packet(ObjectEnums{server_offered_types()});
}

bool ServerSession::passes_filter(ItemType type, std::uint32_t filter_id) const {
  const auto it = filter_.find(to_u32(type));
  return it == filter_.end() || it->second.contains(filter_id);
}

Result<Packets> ServerSession::on_client_packet(std::span<const std::byte> body,
                                                const ServedFrame* latest) {
  auto items = split_items(body);
  if (!items) return items.error();
  Packets out;
  for (const RawItem& item : items.value()) {
    switch (static_cast<ItemType>(item.type)) {
      case ItemType::object_enums: {
        auto e = parse_item<ObjectEnums>(item.payload, item.offset);
        if (!e) return e.error();
        std::set<std::uint32_t> wanted(e.value().types.begin(), e.value().types.end());
        if (wanted != requested_) {
          requested_ = std::move(wanted);
          held_static_.clear();  // newly requested types must be sent in full (§7 server rules)
        }
        break;
      }
      case ItemType::request_frame: {
        auto r = parse_item<RequestFrame>(item.payload, item.offset);
        if (!r) return r.error();
        streaming_ = r.value().streaming;
        // RequestFrame(0): stop streaming and send the latest frame once, even a repeat (§6.3).
        if (!streaming_ && latest != nullptr) out.push_back(encode_frame(*latest));
        break;
      }
      case ItemType::request_next_frame: {
        auto r = parse_item<RequestNextFrame>(item.payload, item.offset);
        if (!r) return r.error();
        pending_next_ =
            std::min(kMaxPendingNext, pending_next_ + std::min(r.value().count, kMaxPendingNext));
        // §6.4: a frame newer than the last one sent already exists → send it at once.
        if (pending_next_ > 0 && latest != nullptr && latest->sequence > last_sent_sequence_) {
          --pending_next_;
          out.push_back(encode_frame(*latest));
        }
        break;
      }
      case ItemType::ping: {
        auto p = parse_item<Ping>(item.payload, item.offset);
        if (!p) return p.error();
        out.push_back(single_item_packet(p.value()));  // echo, same id (§6.6)
        break;
      }
      case ItemType::filter: {
        auto f = parse_item<Filter>(item.payload, item.offset);
        if (!f) return f.error();
        filter_.clear();
        for (const auto& [type, ids] : f.value().filter) {
          filter_[type] = std::set<std::uint32_t>(ids.begin(), ids.end());
        }
        held_static_.clear();  // forget everything when the filter changes (§7)
        break;
      }
      default:
        // KeepAlive, ApexHaptics, multicast requests (not emulated) and unknown types: ignored.
        break;
    }
  }
  return out;
}

std::optional<std::vector<std::byte>> ServerSession::on_new_frame(const ServedFrame& frame) {
  if (streaming_) return encode_frame(frame);
  if (pending_next_ > 0 && frame.sequence > last_sent_sequence_) {
    --pending_next_;
    return encode_frame(frame);
  }
  return std::nullopt;
}

std::vector<std::byte> ServerSession::encode_frame(const ServedFrame& frame) {
  last_sent_sequence_ = std::max(last_sent_sequence_, frame.sequence);
  const std::set<std::uint32_t> offered = [] {
    const auto v = server_offered_types();
    return std::set<std::uint32_t>(v.begin(), v.end());
  }();

  Contents contents;
  std::vector<std::pair<std::uint32_t, Packets>> sections;  // type → item payloads, ascending
  for (const std::uint32_t type : requested_) {
    if (!offered.contains(type) || type == to_u32(ItemType::contents)) continue;
    Packets items;
    const auto kind = static_cast<ItemType>(type);
    switch (kind) {
      case ItemType::stream_info:
        items.push_back(payload_of(StreamInfo{frame.frame_period_ticks}));
        break;
      case ItemType::subject_info:
        for (const ServedSubject& s : frame.subjects) {
          if (!passes_filter(kind, s.subject_id)) continue;
          SubjectInfo info{s.subject_id, s.name, {SegmentInfo{0, 1, {}, s.name}}, {}, {}};
          items.push_back(payload_of(info));
        }
        break;
      case ItemType::object_quality:
        for (const ServedSubject& s : frame.subjects) {
          if (!passes_filter(kind, s.subject_id)) continue;
          items.push_back(payload_of(ObjectQuality{s.subject_id, s.tracked ? 1.0 : 0.0}));
        }
        break;
      case ItemType::application_info:
        items.push_back(payload_of(ApplicationInfo{0}));  // Z-up
        break;
      case ItemType::frame_info:
        items.push_back(payload_of(FrameInfo{frame.frame_id}));
        break;
      case ItemType::timecode:
        if (frame.timecode) items.push_back(payload_of(*frame.timecode));
        break;
      case ItemType::latency_info:
        if (!frame.latency.empty()) items.push_back(payload_of(LatencyInfo{frame.latency}));
        break;
      case ItemType::frame_rate_info:
        if (frame.frame_period_ticks > 0) {
          const double hz = kStreamClockHz / static_cast<double>(frame.frame_period_ticks);
          items.push_back(payload_of(FrameRateInfo{{{"Frame Rate", hz}}}));
        }
        break;
      case ItemType::global_segments:
      case ItemType::local_segments:  // root segment: local = global (§8.20)
        for (const ServedSubject& s : frame.subjects) {
          if (!passes_filter(kind, s.subject_id)) continue;
          items.push_back(kind == ItemType::global_segments
                              ? payload_of(poses_of<ItemType::global_segments>(s))
                              : payload_of(poses_of<ItemType::local_segments>(s)));
        }
        break;
      default:
        break;
    }
    // Unchanged rule, static types only (§7 server rules; dynamic types would suppress the SDK's
    // network-latency sample).
    if (item_class(type) == ItemClass::static_item) {
      const auto held = held_static_.find(type);
      if (held != held_static_.end() && held->second == items) {
        contents.unchanged.push_back(type);
        contents.table.emplace_back(type, 0);
        continue;
      }
      held_static_[type] = items;
    }
    contents.table.emplace_back(type, static_cast<std::uint32_t>(items.size()));
    sections.emplace_back(type, std::move(items));
  }

  PacketBuilder b;
  b.add(contents);
  for (const auto& [type, items] : sections) {
    for (const auto& payload : items) b.add_raw(type, payload);
  }
  return b.finish();
}

}  // namespace mocaplink::wire::vicon
