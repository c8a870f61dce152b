// The participant on eProsima Fast DDS 2.x (Debian's libfastrtps-dev; docs/architecture.md says
// why this library). Samples arrive encoded (libs/wire/ros2_messages.hpp), so one TopicDataType
// carries opaque bytes under whatever ROS type name the topic has: no generated code, no
// TypeObject or TypeInformation (neither ROS RMW sends them, so readers match on names and QoS).
#include <arpa/inet.h>
#include <ifaddrs.h>
#include <netinet/in.h>

#include <algorithm>
#include <cstring>
#include <mutex>

#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastrtps/config.h>
#include <fastrtps/utils/IPLocator.h>
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/DataWriterListener.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TopicDataType.hpp>

#include "dds.hpp"

namespace mocaplink::ros2::detail {
namespace {

namespace dds = eprosima::fastdds::dds;
using eprosima::fastrtps::rtps::IPLocator;
using eprosima::fastrtps::rtps::Locator_t;

/// Participants on one host that loopback discovery reaches (unicast SPDP to 127.0.0.1 for
/// participant indices 0..N−1): what ROS 2 Jazzy's LOCALHOST range uses (ros2-dds.md §1).
constexpr std::uint32_t kLoopbackPeers = 32;

/// A sample is a std::vector<std::uint8_t> holding the encapsulation header and the payload.
class OpaqueType final : public dds::TopicDataType {
 public:
  OpaqueType(const std::string& name, std::uint32_t max_bytes) {
    setName(name.c_str());
    m_typeSize = max_bytes;
    m_isGetKeyDefined = false;
    auto_fill_type_object(false);
    auto_fill_type_information(false);
  }
  bool serialize(void* data, eprosima::fastrtps::rtps::SerializedPayload_t* payload) override {
    const auto& bytes = *static_cast<const std::vector<std::uint8_t>*>(data);
    if (bytes.size() < 4 || bytes.size() > payload->max_size) return false;
    std::memcpy(payload->data, bytes.data(), bytes.size());
    payload->length = static_cast<std::uint32_t>(bytes.size());
    payload->encapsulation = CDR_LE;
    return true;
  }
  bool deserialize(eprosima::fastrtps::rtps::SerializedPayload_t* payload, void* data) override {
    auto& bytes = *static_cast<std::vector<std::uint8_t>*>(data);
    bytes.assign(payload->data, payload->data + payload->length);
    return true;
  }
  std::function<std::uint32_t()> getSerializedSizeProvider(void* data) override {
    return [data] {
      return static_cast<std::uint32_t>(
          static_cast<const std::vector<std::uint8_t>*>(data)->size());
    };
  }
  void* createData() override { return new std::vector<std::uint8_t>(); }
  void deleteData(void* data) override { delete static_cast<std::vector<std::uint8_t>*>(data); }
  bool getKey(void* /*data*/, eprosima::fastrtps::rtps::InstanceHandle_t* /*handle*/,
              bool /*force_md5*/) override {
    return false;
  }
};

class MatchListener final : public dds::DataWriterListener {
 public:
  explicit MatchListener(std::function<void(std::uint32_t)> on_matched)
      : on_matched_(std::move(on_matched)) {}
  void on_publication_matched(dds::DataWriter* /*writer*/,
                              const dds::PublicationMatchedStatus& info) override {
    if (on_matched_) on_matched_(static_cast<std::uint32_t>(std::max(0, info.current_count)));
  }

 private:
  std::function<void(std::uint32_t)> on_matched_;
};

class FastDdsWriter final : public Writer {
 public:
  FastDdsWriter(dds::DomainParticipant* participant, dds::Publisher* publisher, dds::Topic* topic,
                dds::DataWriter* writer, std::unique_ptr<MatchListener> listener)
      : participant_(participant),
        publisher_(publisher),
        topic_(topic),
        writer_(writer),
        listener_(std::move(listener)) {}
  ~FastDdsWriter() override {
    (void)publisher_->delete_datawriter(writer_);
    (void)participant_->delete_topic(topic_);
  }
  bool write(std::span<const std::uint8_t> sample) override {
    sample_.assign(sample.begin(), sample.end());
    return writer_->write(&sample_);
  }

 private:
  dds::DomainParticipant* participant_;
  dds::Publisher* publisher_;
  dds::Topic* topic_;
  dds::DataWriter* writer_;
  std::unique_ptr<MatchListener> listener_;  // outlives the DataWriter (deleted first)
  std::vector<std::uint8_t> sample_;
};

class ReadListener final : public dds::DataReaderListener {
 public:
  explicit ReadListener(const ReaderSettings& settings) : on_sample_(settings.on_sample) {}
  void on_data_available(dds::DataReader* reader) override {
    dds::SampleInfo info;
    while (reader->take_next_sample(&sample_, &info) ==
           eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK) {
      if (info.valid_data && on_sample_) on_sample_(sample_);
    }
  }

 private:
  std::function<void(std::span<const std::uint8_t>)> on_sample_;
  std::vector<std::uint8_t> sample_;  // the DDS thread's own
};

class FastDdsReader final : public Reader {
 public:
  FastDdsReader(dds::DomainParticipant* participant, dds::Subscriber* subscriber, dds::Topic* topic,
                dds::DataReader* reader, std::unique_ptr<ReadListener> listener)
      : participant_(participant),
        subscriber_(subscriber),
        topic_(topic),
        reader_(reader),
        listener_(std::move(listener)) {}
  ~FastDdsReader() override {
    // Detached first: Fast DDS waits for a listener call in progress, then calls no more.
    (void)reader_->set_listener(nullptr);
    (void)subscriber_->delete_datareader(reader_);
    (void)participant_->delete_topic(topic_);
  }

 private:
  dds::DomainParticipant* participant_;
  dds::Subscriber* subscriber_;
  dds::Topic* topic_;
  dds::DataReader* reader_;
  std::unique_ptr<ReadListener> listener_;  // outlives the DataReader
};

/// This machine's IPv4 addresses ("127.0.0.1, 192.168.1.10").
std::vector<std::string> local_ipv4_addresses() {
  std::vector<std::string> out;
  ifaddrs* list = nullptr;
  if (getifaddrs(&list) != 0) return out;
  for (const ifaddrs* a = list; a != nullptr; a = a->ifa_next) {
    if (a->ifa_addr == nullptr || a->ifa_addr->sa_family != AF_INET) continue;
    char text[INET_ADDRSTRLEN] = {};
    const auto* in = reinterpret_cast<const sockaddr_in*>(a->ifa_addr);
    if (inet_ntop(AF_INET, &in->sin_addr, text, sizeof text) != nullptr) out.emplace_back(text);
  }
  freeifaddrs(list);
  return out;
}

Locator_t udp_locator(const std::string& address) {
  Locator_t locator;
  IPLocator::setIPv4(locator, address);
  locator.port = 0;  // Fast DDS fills in the well-known ports of the domain (and the peer range)
  return locator;
}

class FastDdsParticipant final : public Participant {
 public:
  static std::unique_ptr<FastDdsParticipant> make(const ParticipantSettings& settings,
                                                  std::string& error) {
    dds::DomainParticipantQos qos;
    qos.name(settings.name);
    // Both RMWs announce the enclave; harmless for plain DDS peers (ros2-dds.md §1).
    const std::string enclave = "enclave=/;";
    qos.user_data().data_vec(
        std::vector<eprosima::fastrtps::rtps::octet>(enclave.begin(), enclave.end()));
    // UDPv4 only: shared memory between different Fast DDS versions is not something to rely on.
    auto udp = std::make_shared<eprosima::fastdds::rtps::UDPv4TransportDescriptor>();
    qos.transport().use_builtin_transports = false;
    auto& builtin = qos.wire_protocol().builtin;
    if (settings.network_interface == "loopback") {
      udp->interfaceWhiteList.emplace_back("127.0.0.1");
      udp->maxInitialPeersRange = kLoopbackPeers;
      // No multicast at all: discovery by unicast to this host's well-known ports.
      builtin.metatrafficUnicastLocatorList.push_back(udp_locator("127.0.0.1"));
      builtin.initialPeersList.push_back(udp_locator("127.0.0.1"));
      qos.wire_protocol().default_unicast_locator_list.push_back(udp_locator("127.0.0.1"));
    } else if (settings.network_interface != "all") {
      // Fast DDS given an address no interface has says so and then uses every interface: the
      // traffic the user did not ask for. Refuse it here instead.
      const auto local = local_ipv4_addresses();
      if (std::find(local.begin(), local.end(), settings.network_interface) == local.end()) {
        std::string list;
        for (const auto& a : local) list += (list.empty() ? "" : ", ") + a;
        error = settings.network_interface + " is not an address of this machine (its addresses: " +
                (list.empty() ? "none" : list) + "); set [ros2] interface to one of them";
        return nullptr;
      }
      udp->interfaceWhiteList.emplace_back(settings.network_interface);
    }
    qos.transport().user_transports.push_back(udp);
    auto* factory = dds::DomainParticipantFactory::get_instance();
    dds::DomainParticipant* participant =
        factory->create_participant(static_cast<dds::DomainId_t>(settings.domain_id), qos);
    if (participant == nullptr) {
      error = "Fast DDS could not create a participant on domain " +
              std::to_string(settings.domain_id) + " (interface " + settings.network_interface +
              "): is that an address of this machine, and are its ports free?";
      return nullptr;
    }
    dds::Publisher* publisher = participant->create_publisher(dds::PUBLISHER_QOS_DEFAULT);
    dds::Subscriber* subscriber = participant->create_subscriber(dds::SUBSCRIBER_QOS_DEFAULT);
    if (publisher == nullptr || subscriber == nullptr) {
      (void)participant->delete_contained_entities();
      (void)factory->delete_participant(participant);
      error = "Fast DDS could not create a publisher and a subscriber";
      return nullptr;
    }
    return std::unique_ptr<FastDdsParticipant>(
        new FastDdsParticipant(participant, publisher, subscriber));
  }

  ~FastDdsParticipant() override {
    (void)participant_->delete_contained_entities();
    (void)dds::DomainParticipantFactory::get_instance()->delete_participant(participant_);
  }

  std::unique_ptr<Writer> make_writer(const WriterSettings& settings, std::string& error) override {
    const std::lock_guard lock(mutex_);
    dds::Topic* topic = topic_for(settings.topic, settings.type, settings.max_sample_bytes, error);
    if (topic == nullptr) return nullptr;
    dds::DataWriterQos wqos = dds::DATAWRITER_QOS_DEFAULT;
    // What every subscriber matches (ros2-dds.md §2): reliable reaches reliable and best-effort
    // readers; volatile reaches volatile ones (tf2's and rclcpp's defaults); keep-last never
    // blocks a write. XCDR1, as both RMWs require.
    wqos.reliability().kind = dds::RELIABLE_RELIABILITY_QOS;
    wqos.durability().kind = dds::VOLATILE_DURABILITY_QOS;
    wqos.history().kind = dds::KEEP_LAST_HISTORY_QOS;
    wqos.history().depth = static_cast<std::int32_t>(settings.depth);
    wqos.representation().m_value.clear();
    wqos.representation().m_value.push_back(dds::XCDR_DATA_REPRESENTATION);
    // Grown as used: a /tf sample may be large, and most are small.
    wqos.endpoint().history_memory_policy = eprosima::fastrtps::rtps::DYNAMIC_REUSABLE_MEMORY_MODE;
    auto listener = std::make_unique<MatchListener>(settings.on_matched);
    dds::DataWriter* dw = publisher_->create_datawriter(topic, wqos, listener.get());
    if (dw == nullptr) {
      (void)participant_->delete_topic(topic);
      error = "cannot create a writer for " + settings.topic;
      return nullptr;
    }
    auto result =
        std::make_unique<FastDdsWriter>(participant_, publisher_, topic, dw, std::move(listener));
    return result;
  }

  std::unique_ptr<Reader> make_reader(const ReaderSettings& settings, std::string& error) override {
    const std::lock_guard lock(mutex_);
    dds::Topic* topic = topic_for(settings.topic, settings.type, settings.max_sample_bytes, error);
    if (topic == nullptr) return nullptr;
    dds::DataReaderQos rqos = dds::DATAREADER_QOS_DEFAULT;
    // Best effort matches every writer; volatile, keep-last: the newest sample is the one wanted.
    rqos.reliability().kind = dds::BEST_EFFORT_RELIABILITY_QOS;
    rqos.durability().kind = dds::VOLATILE_DURABILITY_QOS;
    rqos.history().kind = dds::KEEP_LAST_HISTORY_QOS;
    rqos.history().depth = static_cast<std::int32_t>(settings.depth);
    rqos.type_consistency().representation.m_value.clear();
    rqos.type_consistency().representation.m_value.push_back(dds::XCDR_DATA_REPRESENTATION);
    rqos.endpoint().history_memory_policy = eprosima::fastrtps::rtps::DYNAMIC_REUSABLE_MEMORY_MODE;
    auto listener = std::make_unique<ReadListener>(settings);
    dds::DataReader* dr = subscriber_->create_datareader(topic, rqos, listener.get());
    if (dr == nullptr) {
      (void)participant_->delete_topic(topic);
      error = "cannot create a reader for " + settings.topic;
      return nullptr;
    }
    return std::make_unique<FastDdsReader>(participant_, subscriber_, topic, dr,
                                           std::move(listener));
  }

 private:
  FastDdsParticipant(dds::DomainParticipant* participant, dds::Publisher* publisher,
                     dds::Subscriber* subscriber)
      : participant_(participant), publisher_(publisher), subscriber_(subscriber) {}

  /// A new Topic object for `name` (each writer and reader deletes its own), its type registered
  /// the first time. Under mutex_.
  dds::Topic* topic_for(const std::string& name, const std::string& type_name,
                        std::uint32_t max_bytes, std::string& error) {
    if (participant_->find_type(type_name).empty()) {
      dds::TypeSupport type(new OpaqueType(type_name, max_bytes));
      if (type.register_type(participant_) != eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK) {
        error = "cannot register type " + type_name;
        return nullptr;
      }
    }
    dds::Topic* topic = participant_->create_topic(name, type_name, dds::TOPIC_QOS_DEFAULT);
    if (topic == nullptr) error = "cannot create topic " + name;
    return topic;
  }

  std::mutex mutex_;
  dds::DomainParticipant* participant_;
  dds::Publisher* publisher_;
  dds::Subscriber* subscriber_;
};

}  // namespace

bool dds_available() {
  return true;
}

std::string dds_implementation() {
  return "Fast DDS " FASTRTPS_VERSION_STR;
}

std::unique_ptr<Participant> make_participant(const ParticipantSettings& settings,
                                              std::string& error) {
  return FastDdsParticipant::make(settings, error);
}

}  // namespace mocaplink::ros2::detail
