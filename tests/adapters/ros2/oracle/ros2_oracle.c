/* mocaplink_ros2_oracle: an independent ROS 2-compatible DDS subscriber for the tests of
 * adapters/ros2. It uses Eclipse Cyclone DDS 0.10 (the DDS that rmw_cyclonedds builds on), not the
 * Fast DDS that mocaplink publishes with, and types compiled by idlc from ros2_types.idl, so a
 * publisher that this program decodes is readable by a second vendor with ROS's type names.
 *
 *   mocaplink_ros2_oracle --count N --timeout SECONDS --sub KIND:DDS_TOPIC [--sub ...]
 *                         [--domain D] [--reliability reliable|best_effort] [--depth N]
 *                         [--durability volatile|transient_local]
 *                         [--px4 NAMESPACE [--px4-armed 0|1] [--px4-nav-state N]
 *                          [--px4-yaw-offset DEG] [--px4-rate HZ]]
 *
 * KIND: pose (geometry_msgs/PoseStamped), odom (nav_msgs/Odometry), tf (tf2_msgs/TFMessage),
 * px4odom (px4_msgs/VehicleOdometry). DDS_TOPIC is the DDS name, e.g. rt/mocap/Body1/pose.
 * Reader QoS: the given reliability (default reliable) and durability (default volatile),
 * keep-last depth (default 10, tf 100; --depth sets every reader), data representation XCDR1 only
 * (as rmw_cyclonedds). Discovery and data stay on 127.0.0.1: unicast only, participant index
 * auto (0..32), peer 127.0.0.1, no shared memory, and no XTypes type information is sent (idlc -t),
 * so matching is by topic name, type name and QoS, as with ROS's RMWs.
 *
 * --px4 plays PX4's side of uXRCE-DDS for one namespace ("-" for none), as PX4's client and
 * Agent present it (PX4-Autopilot v1.14 dds_topics.yaml, msg/templates/ucdr): it reads
 * rt/NS/fmu/in/vehicle_visual_odometry (a px4odom --sub added by itself, best effort like the
 * Agent's reader unless --reliability says otherwise) and writes, best effort, v1.14's
 * rt/NS/fmu/out/vehicle_status at 2 Hz (arming_state 2 with --px4-armed 1, else 1; nav_state
 * default 2, POSCTL) and, once a vision pose has arrived, rt/NS/fmu/out/vehicle_odometry at
 * --px4-rate (default 50 Hz): an estimator that fuses the last pose exactly, in NED
 * (pose_frame 1, velocity_frame 1), turned about the down axis by --px4-yaw-offset degrees
 * (default 0: a vehicle whose estimate agrees with mocap). Outgoing `timestamp` is this host's
 * wall clock in us, as PX4 converts it for the Agent's host; timestamp_sample is the pose's.
 *
 * Output: one JSON object per line on stdout.
 *   {"event":"ready",...}                     readers created
 *   {"event":"matched"|"unmatched","topic":...,"type":...,"current_count":..,"total_count":..}
 *   {"event":"incompatible_qos","topic":...,"type":...,"policy":"reliability",..,"policy_id":..,
 *    "total_count":..}                       a writer on the topic offers QoS we cannot accept
 *   {"topic":...,"type":...,"n":..,"source_timestamp_ns":..,"receive_time_ns":.., <message>}
 *      where <message> is every field of the ROS message under its ROS name; doubles %.17g,
 *      floats %.9g, non-finite values as the strings "nan", "inf", "-inf"; receive_time_ns is
 *      CLOCK_REALTIME when the sample was taken.
 *   {"event":"done"|"timeout","subs":[{"topic":..,"type":..,"received":..,"matched":..},..]
 *    [,"px4":{"status_written":..,"odometry_written":..}]}
 * Exit status: 0 once every --sub received --count samples; 3 on timeout; 2 on bad arguments;
 * 1 on a DDS error. */

#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include <dds/dds.h>

#include "ros2_types.h"

enum kind { KIND_POSE, KIND_ODOM, KIND_TF, KIND_PX4ODOM };

struct kind_info {
  const char* name;
  const char* ros_type; /* DDS type name as ROS's RMWs spell it */
  const dds_topic_descriptor_t* desc;
  uint32_t default_depth;
};

static const struct kind_info kinds[] = {
    [KIND_POSE] = {"pose", "geometry_msgs::msg::dds_::PoseStamped_",
                   &geometry_msgs_msg_PoseStamped_desc, 10},
    [KIND_ODOM] = {"odom", "nav_msgs::msg::dds_::Odometry_", &nav_msgs_msg_Odometry_desc, 10},
    [KIND_TF] = {"tf", "tf2_msgs::msg::dds_::TFMessage_", &tf2_msgs_msg_TFMessage_desc, 100},
    [KIND_PX4ODOM] = {"px4odom", "px4_msgs::msg::dds_::VehicleOdometry_",
                      &px4_msgs_msg_VehicleOdometry_desc, 10},
};
#define NKINDS (sizeof kinds / sizeof kinds[0])

#define MAX_SUBS 64

struct sub {
  enum kind kind;
  const char* topic_name;
  dds_topic_descriptor_t* desc; /* copy of the idlc descriptor with the ROS type name */
  dds_entity_t topic, reader, readcond;
  uint64_t received;
  uint32_t matched;
};

static struct sub subs[MAX_SUBS];
static size_t nsubs;

/* The PX4 stand-in of --px4. */
struct px4 {
  bool on, armed;
  uint8_t nav_state;
  double yaw_offset_rad, rate_hz;
  char vision_topic[256], status_topic[256], odometry_topic[256];
  struct sub* vision; /* the px4odom sub on vision_topic */
  dds_topic_descriptor_t *status_desc, *odometry_desc;
  dds_entity_t status_writer, odometry_writer;
  px4_msgs_msg_VehicleOdometry last; /* the last vision pose, a flat struct */
  bool have_last;
  uint64_t status_written, odometry_written;
};

static struct px4 px4 = {.nav_state = 2, .rate_hz = 50.0};

/* Loopback only: one interface 127.0.0.1, no multicast at all, unicast discovery to 127.0.0.1
 * on the ports of participant indices 0..32, and our own index chosen automatically so that
 * peers (ours or another vendor's) find us on a predictable port. */
static const char domain_config[] =
    "<CycloneDDS><Domain Id=\"any\">"
    "<General>"
    "<Interfaces><NetworkInterface address=\"127.0.0.1\"/></Interfaces>"
    "<AllowMulticast>false</AllowMulticast>"
    "</General>"
    "<Discovery>"
    "<ParticipantIndex>auto</ParticipantIndex>"
    "<MaxAutoParticipantIndex>32</MaxAutoParticipantIndex>"
    "<Peers><Peer address=\"127.0.0.1\"/></Peers>"
    "</Discovery>"
    "<SharedMemory><Enable>false</Enable></SharedMemory>"
    "</Domain></CycloneDDS>";

static void usage(FILE* f) {
  fprintf(f,
          "usage: mocaplink_ros2_oracle --count N --timeout SECONDS --sub KIND:DDS_TOPIC "
          "[--sub ...]\n"
          "                             [--domain D] [--reliability reliable|best_effort]\n"
          "                             [--depth N] [--durability volatile|transient_local]\n"
          "  KIND: pose (geometry_msgs/PoseStamped), odom (nav_msgs/Odometry),\n"
          "        tf (tf2_msgs/TFMessage), px4odom (px4_msgs/VehicleOdometry)\n"
          "  DDS_TOPIC: e.g. rt/mocap/Body1/pose, rt/tf, rt/fmu/in/vehicle_visual_odometry\n"
          "  --px4 NAMESPACE (- for none): play PX4's uXRCE-DDS side (see the source)\n"
          "  defaults: domain 0, reliable, volatile, depth 10 (tf 100)\n"
          "  exit: 0 all samples received, 3 timeout, 2 bad arguments, 1 DDS error\n");
}

static int bad_args(const char* what, const char* value) {
  fprintf(stderr, "mocaplink_ros2_oracle: %s%s%s\n", what, value ? ": " : "", value ? value : "");
  usage(stderr);
  return 2;
}

static bool parse_u64(const char* s, uint64_t max, uint64_t* out) {
  if (s == NULL || *s == '\0' || *s == '-' || *s == '+') return false;
  char* end = NULL;
  errno = 0;
  unsigned long long v = strtoull(s, &end, 10);
  if (errno != 0 || *end != '\0' || v > max) return false;
  *out = (uint64_t)v;
  return true;
}

static int64_t now_realtime_ns(void) {
  struct timespec ts;
  clock_gettime(CLOCK_REALTIME, &ts);
  return (int64_t)ts.tv_sec * 1000000000 + (int64_t)ts.tv_nsec;
}

static int64_t now_monotonic_ns(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (int64_t)ts.tv_sec * 1000000000 + (int64_t)ts.tv_nsec;
}

/* ---- JSON output ---- */

static void put_str(const char* s) {
  putchar('"');
  for (const unsigned char* p = (const unsigned char*)(s ? s : ""); *p; p++) {
    if (*p == '"' || *p == '\\') {
      putchar('\\');
      putchar(*p);
    } else if (*p < 0x20 || *p == 0x7f) {
      printf("\\u%04x", (unsigned)*p);
    } else {
      putchar(*p);
    }
  }
  putchar('"');
}

static void put_nonfinite(double v) {
  fputs(isnan(v) ? "\"nan\"" : (v > 0 ? "\"inf\"" : "\"-inf\""), stdout);
}

static void put_f64(double v) {
  if (!isfinite(v)) {
    put_nonfinite(v);
    return;
  }
  printf("%.17g", v);
}

static void put_f32(float f) {
  double v = (double)f;
  if (!isfinite(v)) {
    put_nonfinite(v);
    return;
  }
  printf("%.9g", v);
}

static void put_f64_array(const double* a, size_t n) {
  putchar('[');
  for (size_t i = 0; i < n; i++) {
    if (i) putchar(',');
    put_f64(a[i]);
  }
  putchar(']');
}

static void put_f32_array(const float* a, size_t n) {
  putchar('[');
  for (size_t i = 0; i < n; i++) {
    if (i) putchar(',');
    put_f32(a[i]);
  }
  putchar(']');
}

static void put_header(const std_msgs_msg_Header* h) {
  printf("{\"stamp\":{\"sec\":%" PRId32 ",\"nanosec\":%" PRIu32 "},\"frame_id\":", h->stamp.sec,
         h->stamp.nanosec);
  put_str(h->frame_id);
  putchar('}');
}

static void put_xyz(const char* name, double x, double y, double z) {
  printf("\"%s\":{\"x\":", name);
  put_f64(x);
  fputs(",\"y\":", stdout);
  put_f64(y);
  fputs(",\"z\":", stdout);
  put_f64(z);
  putchar('}');
}

static void put_quat(const char* name, const geometry_msgs_msg_Quaternion* q) {
  printf("\"%s\":{\"x\":", name);
  put_f64(q->x);
  fputs(",\"y\":", stdout);
  put_f64(q->y);
  fputs(",\"z\":", stdout);
  put_f64(q->z);
  fputs(",\"w\":", stdout);
  put_f64(q->w);
  putchar('}');
}

static void put_pose(const geometry_msgs_msg_Pose* p) {
  putchar('{');
  put_xyz("position", p->position.x, p->position.y, p->position.z);
  putchar(',');
  put_quat("orientation", &p->orientation);
  putchar('}');
}

static void put_twist(const geometry_msgs_msg_Twist* t) {
  putchar('{');
  put_xyz("linear", t->linear.x, t->linear.y, t->linear.z);
  putchar(',');
  put_xyz("angular", t->angular.x, t->angular.y, t->angular.z);
  putchar('}');
}

static void put_transform_stamped(const geometry_msgs_msg_TransformStamped* t) {
  fputs("{\"header\":", stdout);
  put_header(&t->header);
  fputs(",\"child_frame_id\":", stdout);
  put_str(t->child_frame_id);
  fputs(",\"transform\":{", stdout);
  put_xyz("translation", t->transform.translation.x, t->transform.translation.y,
          t->transform.translation.z);
  putchar(',');
  put_quat("rotation", &t->transform.rotation);
  fputs("}}", stdout);
}

static void put_message(enum kind kind, const void* sample) {
  switch (kind) {
    case KIND_POSE: {
      const geometry_msgs_msg_PoseStamped* m = sample;
      fputs("\"header\":", stdout);
      put_header(&m->header);
      fputs(",\"pose\":", stdout);
      put_pose(&m->pose);
      break;
    }
    case KIND_ODOM: {
      const nav_msgs_msg_Odometry* m = sample;
      fputs("\"header\":", stdout);
      put_header(&m->header);
      fputs(",\"child_frame_id\":", stdout);
      put_str(m->child_frame_id);
      fputs(",\"pose\":{\"pose\":", stdout);
      put_pose(&m->pose.pose);
      fputs(",\"covariance\":", stdout);
      put_f64_array(m->pose.covariance, 36);
      fputs("},\"twist\":{\"twist\":", stdout);
      put_twist(&m->twist.twist);
      fputs(",\"covariance\":", stdout);
      put_f64_array(m->twist.covariance, 36);
      putchar('}');
      break;
    }
    case KIND_TF: {
      const tf2_msgs_msg_TFMessage* m = sample;
      fputs("\"transforms\":[", stdout);
      for (uint32_t i = 0; i < m->transforms._length; i++) {
        if (i) putchar(',');
        put_transform_stamped(&m->transforms._buffer[i]);
      }
      putchar(']');
      break;
    }
    case KIND_PX4ODOM: {
      const px4_msgs_msg_VehicleOdometry* m = sample;
      printf("\"timestamp\":%" PRIu64 ",\"timestamp_sample\":%" PRIu64 ",\"pose_frame\":%u",
             m->timestamp, m->timestamp_sample, (unsigned)m->pose_frame);
      fputs(",\"position\":", stdout);
      put_f32_array(m->position, 3);
      fputs(",\"q\":", stdout);
      put_f32_array(m->q, 4);
      printf(",\"velocity_frame\":%u", (unsigned)m->velocity_frame);
      fputs(",\"velocity\":", stdout);
      put_f32_array(m->velocity, 3);
      fputs(",\"angular_velocity\":", stdout);
      put_f32_array(m->angular_velocity, 3);
      fputs(",\"position_variance\":", stdout);
      put_f32_array(m->position_variance, 3);
      fputs(",\"orientation_variance\":", stdout);
      put_f32_array(m->orientation_variance, 3);
      fputs(",\"velocity_variance\":", stdout);
      put_f32_array(m->velocity_variance, 3);
      printf(",\"reset_counter\":%u,\"quality\":%d", (unsigned)m->reset_counter, (int)m->quality);
      break;
    }
  }
}

static void put_sub_prefix(const char* event, const struct sub* s) {
  if (event)
    printf("{\"event\":\"%s\",", event);
  else
    putchar('{');
  fputs("\"topic\":", stdout);
  put_str(s->topic_name);
  printf(",\"type\":\"%s\"", kinds[s->kind].name);
}

static void put_summary(const char* event) {
  printf("{\"event\":\"%s\",\"subs\":[", event);
  for (size_t i = 0; i < nsubs; i++) {
    if (i) putchar(',');
    put_sub_prefix(NULL, &subs[i]);
    printf(",\"received\":%" PRIu64 ",\"matched\":%" PRIu32 "}", subs[i].received, subs[i].matched);
  }
  putchar(']');
  if (px4.on)
    printf(",\"px4\":{\"status_written\":%" PRIu64 ",\"odometry_written\":%" PRIu64 "}",
           px4.status_written, px4.odometry_written);
  fputs("}\n", stdout);
  fflush(stdout);
}

/* ---- DDS ---- */

static dds_topic_descriptor_t* ros_descriptor(const dds_topic_descriptor_t* d,
                                              const char* ros_type) {
  /* The members are const: build a new descriptor by initialisation, identical but for the
   * type name. */
  dds_topic_descriptor_t tmp = {
      .m_size = d->m_size,
      .m_align = d->m_align,
      .m_flagset = d->m_flagset,
      .m_nkeys = d->m_nkeys,
      .m_typename = ros_type,
      .m_keys = d->m_keys,
      .m_nops = d->m_nops,
      .m_ops = d->m_ops,
      .m_meta = d->m_meta,
      .type_information = d->type_information,
      .type_mapping = d->type_mapping,
      .restrict_data_representation = d->restrict_data_representation,
  };
  dds_topic_descriptor_t* copy = malloc(sizeof *copy);
  if (copy) memcpy(copy, &tmp, sizeof tmp);
  return copy;
}

static bool drain(struct sub* s) {
  void* samples[16];
  dds_sample_info_t infos[16];
  bool any = false;
  for (;;) {
    memset(samples, 0, sizeof samples);
    dds_return_t n = dds_take(s->reader, samples, infos, 16, 16);
    if (n < 0) {
      fprintf(stderr, "mocaplink_ros2_oracle: dds_take: %s\n", dds_strretcode(n));
      return any;
    }
    if (n == 0) break;
    int64_t received_at = now_realtime_ns();
    for (int32_t i = 0; i < n; i++) {
      if (!infos[i].valid_data) continue;
      s->received++;
      put_sub_prefix(NULL, s);
      printf(",\"n\":%" PRIu64 ",\"source_timestamp_ns\":%" PRId64 ",\"receive_time_ns\":%" PRId64
             ",",
             s->received, (int64_t)infos[i].source_timestamp, received_at);
      put_message(s->kind, samples[i]);
      fputs("}\n", stdout);
      if (s == px4.vision) {
        px4.last = *(const px4_msgs_msg_VehicleOdometry*)samples[i];
        px4.have_last = true;
      }
      any = true;
    }
    fflush(stdout);
    dds_return_loan(s->reader, samples, n);
    if (n < 16) break;
  }
  return any;
}

static const char* policy_name(uint32_t id) {
  switch (id) {
    case DDS_DURABILITY_QOS_POLICY_ID:
      return "durability";
    case DDS_DEADLINE_QOS_POLICY_ID:
      return "deadline";
    case DDS_LATENCYBUDGET_QOS_POLICY_ID:
      return "latency_budget";
    case DDS_OWNERSHIP_QOS_POLICY_ID:
      return "ownership";
    case DDS_LIVELINESS_QOS_POLICY_ID:
      return "liveliness";
    case DDS_PARTITION_QOS_POLICY_ID:
      return "partition";
    case DDS_RELIABILITY_QOS_POLICY_ID:
      return "reliability";
    case DDS_DESTINATIONORDER_QOS_POLICY_ID:
      return "destination_order";
    case DDS_PRESENTATION_QOS_POLICY_ID:
      return "presentation";
    case DDS_DATA_REPRESENTATION_QOS_POLICY_ID:
      return "data_representation";
    case DDS_TYPE_CONSISTENCY_ENFORCEMENT_QOS_POLICY_ID:
      return "type_consistency";
    default:
      return "other";
  }
}

static void report_status(struct sub* s) {
  uint32_t st = 0;
  if (dds_take_status(s->reader, &st,
                      DDS_SUBSCRIPTION_MATCHED_STATUS | DDS_REQUESTED_INCOMPATIBLE_QOS_STATUS) < 0)
    return;
  if (st & DDS_SUBSCRIPTION_MATCHED_STATUS) {
    dds_subscription_matched_status_t m;
    if (dds_get_subscription_matched_status(s->reader, &m) == 0) {
      s->matched = m.current_count;
      put_sub_prefix(m.current_count_change < 0 ? "unmatched" : "matched", s);
      printf(",\"current_count\":%" PRIu32 ",\"total_count\":%" PRIu32 "}\n", m.current_count,
             m.total_count);
      fflush(stdout);
    }
  }
  if (st & DDS_REQUESTED_INCOMPATIBLE_QOS_STATUS) {
    dds_requested_incompatible_qos_status_t q;
    if (dds_get_requested_incompatible_qos_status(s->reader, &q) == 0) {
      put_sub_prefix("incompatible_qos", s);
      printf(",\"policy\":\"%s\",\"policy_id\":%" PRIu32 ",\"total_count\":%" PRIu32 "}\n",
             policy_name(q.last_policy_id), q.last_policy_id, q.total_count);
      fflush(stdout);
    }
  }
}

/* ---- the PX4 stand-in ---- */

static uint64_t now_realtime_us(void) {
  return (uint64_t)(now_realtime_ns() / 1000);
}

/* Hamilton product a*b of {w, x, y, z}. */
static void quat_mul(const double a[4], const double b[4], double out[4]) {
  out[0] = a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3];
  out[1] = a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2];
  out[2] = a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1];
  out[3] = a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0];
}

/* v rotated by the unit quaternion q {w, x, y, z}: q v q*. */
static void quat_rotate(const double q[4], const double v[3], double out[3]) {
  const double p[4] = {0.0, v[0], v[1], v[2]};
  const double conj[4] = {q[0], -q[1], -q[2], -q[3]};
  double t[4], r[4];
  quat_mul(q, p, t);
  quat_mul(t, conj, r);
  out[0] = r[1];
  out[1] = r[2];
  out[2] = r[3];
}

static dds_entity_t px4_writer(dds_entity_t participant, const dds_topic_descriptor_t* desc,
                               const char* topic_name) {
  dds_entity_t topic = dds_create_topic(participant, desc, topic_name, NULL, NULL);
  if (topic < 0) {
    fprintf(stderr, "mocaplink_ros2_oracle: dds_create_topic %s: %s\n", topic_name,
            dds_strretcode(topic));
    return topic;
  }
  dds_qos_t* qos = dds_create_qos();
  dds_qset_reliability(qos, DDS_RELIABILITY_BEST_EFFORT, 0);
  dds_qset_durability(qos, DDS_DURABILITY_VOLATILE);
  dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, 1);
  const dds_data_representation_id_t xcdr1[] = {DDS_DATA_REPRESENTATION_XCDR1};
  dds_qset_data_representation(qos, 1, xcdr1);
  dds_entity_t writer = dds_create_writer(participant, topic, qos, NULL);
  dds_delete_qos(qos);
  if (writer < 0)
    fprintf(stderr, "mocaplink_ros2_oracle: dds_create_writer %s: %s\n", topic_name,
            dds_strretcode(writer));
  return writer;
}

static bool px4_start(dds_entity_t participant) {
  px4.status_desc =
      ros_descriptor(&px4_msgs_msg_VehicleStatus_desc, "px4_msgs::msg::dds_::VehicleStatus_");
  px4.odometry_desc =
      ros_descriptor(&px4_msgs_msg_VehicleOdometry_desc, "px4_msgs::msg::dds_::VehicleOdometry_");
  if (px4.status_desc == NULL || px4.odometry_desc == NULL) return false;
  px4.status_writer = px4_writer(participant, px4.status_desc, px4.status_topic);
  px4.odometry_writer = px4_writer(participant, px4.odometry_desc, px4.odometry_topic);
  return px4.status_writer >= 0 && px4.odometry_writer >= 0;
}

static void px4_write_status(void) {
  px4_msgs_msg_VehicleStatus m;
  memset(&m, 0, sizeof m);
  m.timestamp = now_realtime_us();
  m.arming_state = px4.armed ? 2 : 1; /* ARMING_STATE_ARMED : ARMING_STATE_STANDBY */
  m.nav_state = px4.nav_state;
  m.nav_state_user_intention = px4.nav_state;
  m.vehicle_type = 1; /* VEHICLE_TYPE_ROTARY_WING */
  m.system_type = 2;  /* MAV_TYPE_QUADROTOR */
  m.system_id = 1;
  m.component_id = 1;
  m.pre_flight_checks_pass = true;
  m.power_input_valid = true;
  if (dds_write(px4.status_writer, &m) == 0) px4.status_written++;
}

/* The last vision pose as a perfect estimator's output, turned by the yaw offset. */
static void px4_write_odometry(void) {
  if (!px4.have_last) return;
  const px4_msgs_msg_VehicleOdometry* in = &px4.last;
  const double h = px4.yaw_offset_rad / 2.0;
  const double turn[4] = {cos(h), 0.0, 0.0, sin(h)};
  const double q_in[4] = {(double)in->q[0], (double)in->q[1], (double)in->q[2], (double)in->q[3]};
  double q[4];
  quat_mul(turn, q_in, q);
  const double p_in[3] = {(double)in->position[0], (double)in->position[1],
                          (double)in->position[2]};
  double p[3];
  quat_rotate(turn, p_in, p);
  const double v_in[3] = {(double)in->velocity[0], (double)in->velocity[1],
                          (double)in->velocity[2]};
  double v[3];
  if (in->velocity_frame == 3)
    quat_rotate(q, v_in, v); /* body FRD -> NED */
  else
    quat_rotate(turn, v_in, v);

  px4_msgs_msg_VehicleOdometry m;
  memset(&m, 0, sizeof m);
  m.timestamp = now_realtime_us();
  m.timestamp_sample = in->timestamp_sample;
  m.pose_frame = 1;     /* POSE_FRAME_NED */
  m.velocity_frame = 1; /* VELOCITY_FRAME_NED */
  for (int i = 0; i < 3; i++) {
    m.position[i] = (float)p[i];
    m.velocity[i] = (float)v[i];
    m.angular_velocity[i] = in->angular_velocity[i];
    m.position_variance[i] = 1e-4f;
    m.orientation_variance[i] = 1e-4f;
    m.velocity_variance[i] = 1e-3f;
  }
  for (int i = 0; i < 4; i++) m.q[i] = (float)q[i];
  m.reset_counter = in->reset_counter;
  if (dds_write(px4.odometry_writer, &m) == 0) px4.odometry_written++;
}

static bool all_done(uint64_t count) {
  for (size_t i = 0; i < nsubs; i++)
    if (subs[i].received < count) return false;
  return true;
}

int main(int argc, char** argv) {
  uint64_t domain = 0, count = 0, depth = 0;
  double timeout_s = -1.0;
  bool reliable = true, transient_local = false, have_count = false, have_depth = false;
  bool have_reliability = false;
  const char* px4_ns = NULL;

  for (int i = 1; i < argc; i++) {
    const char* a = argv[i];
    if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
      usage(stdout);
      return 0;
    }
    if (i + 1 >= argc) return bad_args("missing value for", a);
    const char* v = argv[++i];
    if (strcmp(a, "--domain") == 0) {
      if (!parse_u64(v, 232, &domain)) return bad_args("bad --domain (0..232)", v);
    } else if (strcmp(a, "--count") == 0) {
      if (!parse_u64(v, UINT32_MAX, &count) || count == 0) return bad_args("bad --count", v);
      have_count = true;
    } else if (strcmp(a, "--depth") == 0) {
      if (!parse_u64(v, 100000, &depth) || depth == 0) return bad_args("bad --depth", v);
      have_depth = true;
    } else if (strcmp(a, "--timeout") == 0) {
      char* end = NULL;
      errno = 0;
      timeout_s = strtod(v, &end);
      if (errno != 0 || end == v || *end != '\0' || !(timeout_s > 0.0) || timeout_s > 86400.0)
        return bad_args("bad --timeout (seconds, > 0)", v);
    } else if (strcmp(a, "--reliability") == 0) {
      have_reliability = true;
      if (strcmp(v, "reliable") == 0)
        reliable = true;
      else if (strcmp(v, "best_effort") == 0)
        reliable = false;
      else
        return bad_args("bad --reliability (reliable|best_effort)", v);
    } else if (strcmp(a, "--durability") == 0) {
      if (strcmp(v, "volatile") == 0)
        transient_local = false;
      else if (strcmp(v, "transient_local") == 0)
        transient_local = true;
      else
        return bad_args("bad --durability (volatile|transient_local)", v);
    } else if (strcmp(a, "--px4") == 0) {
      if (*v == '\0' || strlen(v) > 200) return bad_args("bad --px4 (NAMESPACE, - for none)", v);
      px4_ns = v;
    } else if (strcmp(a, "--px4-armed") == 0) {
      if (strcmp(v, "0") != 0 && strcmp(v, "1") != 0) return bad_args("bad --px4-armed (0|1)", v);
      px4.armed = v[0] == '1';
    } else if (strcmp(a, "--px4-nav-state") == 0) {
      uint64_t n = 0;
      if (!parse_u64(v, 255, &n)) return bad_args("bad --px4-nav-state (0..255)", v);
      px4.nav_state = (uint8_t)n;
    } else if (strcmp(a, "--px4-yaw-offset") == 0 || strcmp(a, "--px4-rate") == 0) {
      char* end = NULL;
      errno = 0;
      double d = strtod(v, &end);
      if (errno != 0 || end == v || *end != '\0' || !isfinite(d))
        return bad_args("bad number for", a);
      if (a[6] == 'y') {
        if (fabs(d) > 360.0) return bad_args("bad --px4-yaw-offset (-360..360)", v);
        px4.yaw_offset_rad = d * 3.14159265358979323846 / 180.0;
      } else {
        if (!(d > 0.0) || d > 1000.0) return bad_args("bad --px4-rate (0 < HZ <= 1000)", v);
        px4.rate_hz = d;
      }
    } else if (strcmp(a, "--sub") == 0) {
      const char* colon = strchr(v, ':');
      if (colon == NULL || colon[1] == '\0') return bad_args("bad --sub (KIND:DDS_TOPIC)", v);
      if (nsubs == MAX_SUBS) return bad_args("too many --sub", v);
      size_t klen = (size_t)(colon - v);
      size_t k;
      for (k = 0; k < NKINDS; k++)
        if (strlen(kinds[k].name) == klen && strncmp(kinds[k].name, v, klen) == 0) break;
      if (k == NKINDS) return bad_args("unknown --sub kind (pose|odom|tf|px4odom)", v);
      subs[nsubs].kind = (enum kind)k;
      subs[nsubs].topic_name = colon + 1;
      nsubs++;
    } else {
      return bad_args("unknown option", a);
    }
  }
  if (!have_count) return bad_args("--count is required", NULL);
  if (timeout_s < 0) return bad_args("--timeout is required", NULL);
  if (px4_ns != NULL) {
    const bool none = strcmp(px4_ns, "-") == 0;
    const char* sep = none ? "" : "/";
    const char* ns = none ? "" : px4_ns;
    if (nsubs == MAX_SUBS) return bad_args("too many --sub", px4_ns);
    snprintf(px4.vision_topic, sizeof px4.vision_topic, "rt%s%s/fmu/in/vehicle_visual_odometry",
             sep, ns);
    snprintf(px4.status_topic, sizeof px4.status_topic, "rt%s%s/fmu/out/vehicle_status", sep, ns);
    snprintf(px4.odometry_topic, sizeof px4.odometry_topic, "rt%s%s/fmu/out/vehicle_odometry", sep,
             ns);
    px4.on = true;
    px4.vision = &subs[nsubs];
    subs[nsubs].kind = KIND_PX4ODOM;
    subs[nsubs].topic_name = px4.vision_topic;
    nsubs++;
    if (!have_reliability) reliable = false; /* the Agent's readers are best effort */
  }
  if (nsubs == 0) return bad_args("at least one --sub is required", NULL);

  const dds_domainid_t dom = (dds_domainid_t)domain;
  dds_entity_t domain_entity = dds_create_domain(dom, domain_config);
  if (domain_entity < 0) {
    fprintf(stderr, "mocaplink_ros2_oracle: dds_create_domain: %s\n",
            dds_strretcode(domain_entity));
    return 1;
  }
  dds_entity_t participant = dds_create_participant(dom, NULL, NULL);
  if (participant < 0) {
    fprintf(stderr, "mocaplink_ros2_oracle: dds_create_participant: %s\n",
            dds_strretcode(participant));
    return 1;
  }
  dds_entity_t waitset = dds_create_waitset(participant);
  if (waitset < 0) {
    fprintf(stderr, "mocaplink_ros2_oracle: dds_create_waitset: %s\n", dds_strretcode(waitset));
    return 1;
  }

  int rc = 1;
  for (size_t i = 0; i < nsubs; i++) {
    struct sub* s = &subs[i];
    const struct kind_info* ki = &kinds[s->kind];
    s->desc = ros_descriptor(ki->desc, ki->ros_type);
    if (s->desc == NULL) goto out;
    s->topic = dds_create_topic(participant, s->desc, s->topic_name, NULL, NULL);
    if (s->topic < 0) {
      fprintf(stderr, "mocaplink_ros2_oracle: dds_create_topic %s: %s\n", s->topic_name,
              dds_strretcode(s->topic));
      goto out;
    }
    dds_qos_t* qos = dds_create_qos();
    dds_qset_reliability(qos, reliable ? DDS_RELIABILITY_RELIABLE : DDS_RELIABILITY_BEST_EFFORT,
                         DDS_SECS(1));
    dds_qset_durability(qos,
                        transient_local ? DDS_DURABILITY_TRANSIENT_LOCAL : DDS_DURABILITY_VOLATILE);
    dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, (int32_t)(have_depth ? depth : ki->default_depth));
    const dds_data_representation_id_t xcdr1[] = {DDS_DATA_REPRESENTATION_XCDR1};
    dds_qset_data_representation(qos, 1, xcdr1);
    s->reader = dds_create_reader(participant, s->topic, qos, NULL);
    dds_delete_qos(qos);
    if (s->reader < 0) {
      fprintf(stderr, "mocaplink_ros2_oracle: dds_create_reader %s: %s\n", s->topic_name,
              dds_strretcode(s->reader));
      goto out;
    }
    if (dds_set_status_mask(
            s->reader, DDS_SUBSCRIPTION_MATCHED_STATUS | DDS_REQUESTED_INCOMPATIBLE_QOS_STATUS) < 0)
      goto out;
    s->readcond = dds_create_readcondition(s->reader, DDS_ANY_STATE);
    if (s->readcond < 0 || dds_waitset_attach(waitset, s->reader, (dds_attach_t)i) < 0 ||
        dds_waitset_attach(waitset, s->readcond, (dds_attach_t)i) < 0) {
      fprintf(stderr, "mocaplink_ros2_oracle: waitset setup failed\n");
      goto out;
    }
  }
  if (px4.on && !px4_start(participant)) goto out;
  printf("{\"event\":\"ready\",\"domain\":%" PRIu64
         ",\"reliability\":\"%s\",\"durability\":\"%s\""
         ",\"count\":%" PRIu64 ",\"pid\":%ld}\n",
         domain, reliable ? "reliable" : "best_effort",
         transient_local ? "transient_local" : "volatile", count, (long)getpid());
  fflush(stdout);

  const int64_t deadline = now_monotonic_ns() + (int64_t)(timeout_s * 1e9);
  const int64_t odometry_period = (int64_t)(1e9 / px4.rate_hz), status_period = 500000000;
  int64_t next_odometry = now_monotonic_ns(), next_status = next_odometry;
  rc = 3;
  for (;;) {
    if (px4.on) {
      const int64_t now = now_monotonic_ns();
      if (now >= next_status) {
        px4_write_status();
        next_status += status_period;
      }
      if (now >= next_odometry) {
        px4_write_odometry();
        next_odometry += odometry_period;
        if (next_odometry < now) next_odometry = now + odometry_period;
      }
    }
    for (size_t i = 0; i < nsubs; i++) {
      report_status(&subs[i]);
      drain(&subs[i]);
    }
    if (all_done(count)) {
      put_summary("done");
      rc = 0;
      break;
    }
    int64_t left = deadline - now_monotonic_ns();
    if (left <= 0) {
      put_summary("timeout");
      rc = 3;
      break;
    }
    if (px4.on) {
      const int64_t now = now_monotonic_ns();
      const int64_t next = next_odometry < next_status ? next_odometry : next_status;
      if (next - now < left) left = next - now > 0 ? next - now : 0;
    }
    dds_attach_t triggered[MAX_SUBS * 2];
    dds_return_t n = dds_waitset_wait(waitset, triggered, MAX_SUBS * 2, left);
    if (n < 0) {
      fprintf(stderr, "mocaplink_ros2_oracle: dds_waitset_wait: %s\n", dds_strretcode(n));
      rc = 1;
      break;
    }
  }

out:
  dds_delete(domain_entity);
  for (size_t i = 0; i < nsubs; i++) free(subs[i].desc);
  free(px4.status_desc);
  free(px4.odometry_desc);
  return rc;
}
