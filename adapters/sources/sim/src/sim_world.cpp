#include "mocaplink/sources/sim_world.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <utility>

namespace mocaplink::sources {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kGravity_m_s2 = 9.81;  // only shapes the simulated tilt
constexpr double kBodySpacing_m = 2.5;  // bodies side by side along x, never overlapping

/// SplitMix64 finaliser (Steele, Lea & Flood 2014): a bijective, well-mixing 64-bit hash.
constexpr std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30U)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27U)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31U);
}

/// What a random draw is for; part of the hash so that draws never share bits.
enum class Draw : std::uint64_t { drop = 1, occlude, outlier, outlier_direction, noise_p, noise_q };

/// Uniform in (0, 1), a pure function of its arguments (counter-based generator).
double uniform(std::uint64_t seed, std::uint64_t when, std::uint64_t body, Draw purpose,
               std::uint64_t k = 0) {
  std::uint64_t h = mix(seed);
  h = mix(h ^ when);
  h = mix(h ^ body);
  h = mix(h ^ ((static_cast<std::uint64_t>(purpose) << 8U) | k));
  return (static_cast<double>(h >> 11U) + 0.5) * 0x1p-53;  // 53 random bits, never 0 or 1
}

/// Standard normal via Box–Muller (portable, unlike std::normal_distribution).
double gaussian(std::uint64_t seed, std::uint64_t when, std::uint64_t body, Draw purpose,
                std::uint64_t k) {
  const double u1 = uniform(seed, when, body, purpose, 2 * k);
  const double u2 = uniform(seed, when, body, purpose, 2 * k + 1);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(kTwoPi * u2);
}

Eigen::Vector3d gaussian3(std::uint64_t seed, std::uint64_t when, std::uint64_t body,
                          Draw purpose) {
  return {gaussian(seed, when, body, purpose, 0), gaussian(seed, when, body, purpose, 1),
          gaussian(seed, when, body, purpose, 2)};
}

Eigen::Quaterniond canonical(Eigen::Quaterniond q) {
  q.normalize();
  if (q.w() < 0.0) q.coeffs() = -q.coeffs();
  return q;
}

/// Multirotor attitude flying acceleration `a` with heading `yaw_rad`: body z along a + g·z, body
/// x as close to the heading as the tilt allows (the usual differential-flatness construction).
Eigen::Quaterniond attitude(const Eigen::Vector3d& a, double yaw_rad) {
  const Eigen::Vector3d b3 = (a + Eigen::Vector3d(0.0, 0.0, kGravity_m_s2)).normalized();
  const Eigen::Vector3d heading(std::cos(yaw_rad), std::sin(yaw_rad), 0.0);
  const Eigen::Vector3d b2 = b3.cross(heading).normalized();
  const Eigen::Vector3d b1 = b2.cross(b3);
  Eigen::Matrix3d r;
  r.col(0) = b1;
  r.col(1) = b2;
  r.col(2) = b3;
  return canonical(Eigen::Quaterniond(r));
}

/// Sinusoid s(t) = amp·sin(w·t + phase) with its first two derivatives.
struct Wave {
  double amp, w, phase;
  [[nodiscard]] double p(double t) const { return amp * std::sin(w * t + phase); }
  [[nodiscard]] double v(double t) const { return amp * w * std::cos(w * t + phase); }
  [[nodiscard]] double a(double t) const { return -amp * w * w * std::sin(w * t + phase); }
};

}  // namespace

SimWorld::SimWorld(SimOptions config) : config_(std::move(config)) {
  if (auto problem = validate_sim_options(config_); !problem.empty()) {
    std::fprintf(stderr, "SimWorld: invalid config: %s\n", problem.c_str());
    std::abort();
  }
}

std::string SimWorld::body_name(std::size_t index) {
  return "Body" + std::to_string(index + 1);
}

BodyTruth SimWorld::truth(std::size_t index, double t) const {
  const double lane = static_cast<double>(index / 3);
  const double offset = static_cast<double>(index) - (static_cast<double>(config_.bodies) - 1) / 2;
  const Eigen::Vector3d centre(offset * kBodySpacing_m, 0.0, 0.0);
  BodyTruth out;
  double yaw_rad = 0.0;
  switch (index % 3) {
    case 0: {  // hover
      const Wave x{0.05, kTwoPi * 0.2, lane}, y{0.05, kTwoPi * 0.15, lane + 1.0},
          z{0.03, kTwoPi * 0.25, 0.0};
      out.p_world_m = centre + Eigen::Vector3d(x.p(t), y.p(t), 1.0 + z.p(t));
      out.v_world_m_s = {x.v(t), y.v(t), z.v(t)};
      out.a_world_m_s2 = {x.a(t), y.a(t), z.a(t)};
      yaw_rad = Wave{0.3, kTwoPi * 0.05, 0.0}.p(t) + 0.5 * lane;
      break;
    }
    case 1: {  // circle: cos = sin shifted by pi/2
      const double w = kTwoPi / (8.0 + 2.0 * lane);
      const double half_pi = std::numbers::pi / 2;
      const Wave x{1.0, w, lane + half_pi}, y{1.0, w, lane}, z{0.1, kTwoPi / 10.0, 0.0};
      out.p_world_m = centre + Eigen::Vector3d(x.p(t), y.p(t), 1.2 + z.p(t));
      out.v_world_m_s = {x.v(t), y.v(t), z.v(t)};
      out.a_world_m_s2 = {x.a(t), y.a(t), z.a(t)};
      yaw_rad = std::atan2(out.v_world_m_s.y(), out.v_world_m_s.x());
      break;
    }
    default: {  // figure-eight, lemniscate of Gerono: x = sin θ, y = sin θ cos θ = ½ sin 2θ
      const double w = kTwoPi / (12.0 + 2.0 * lane);
      const Wave x{1.0, w, lane}, y{0.5, 2.0 * w, 2.0 * lane}, z{0.05, kTwoPi / 7.0, 0.0};
      out.p_world_m = centre + Eigen::Vector3d(x.p(t), y.p(t), 1.5 + z.p(t));
      out.v_world_m_s = {x.v(t), y.v(t), z.v(t)};
      out.a_world_m_s2 = {x.a(t), y.a(t), z.a(t)};
      // The horizontal speed never vanishes (cos θ and cos 2θ are never both 0), so yaw is defined.
      yaw_rad = std::atan2(out.v_world_m_s.y(), out.v_world_m_s.x());
      break;
    }
  }
  out.q_world_body = attitude(out.a_world_m_s2, yaw_rad);
  return out;
}

double SimWorld::time_s(std::uint64_t frame_number) const {
  return static_cast<double>(frame_number - 1) / config_.rate_hz;
}

core::SourceTime SimWorld::capture_time(std::uint64_t frame_number) const {
  return core::source_time_from_ns(std::llround(time_s(frame_number) * 1e9));
}

bool SimWorld::dropped(std::uint64_t frame_number) const {
  return config_.drop > 0.0 && uniform(config_.seed, frame_number, 0, Draw::drop) < config_.drop;
}

bool SimWorld::occluded(std::size_t index, std::uint64_t frame_number) const {
  if (config_.occlude <= 0.0) return false;
  const auto slot =
      static_cast<std::uint64_t>(std::floor(time_s(frame_number) / config_.occlude_s));
  return uniform(config_.seed, slot, index, Draw::occlude) < config_.occlude;
}

bool SimWorld::absent(std::size_t index, std::uint64_t frame_number) const {
  if (config_.churn_s <= 0.0 || index + 1 != config_.bodies) return false;
  return static_cast<std::uint64_t>(std::floor(time_s(frame_number) / config_.churn_s)) % 2 == 1;
}

core::MocapFrame SimWorld::frame(std::uint64_t frame_number) const {
  core::MocapFrame frame;
  frame.frame_number = frame_number;
  frame.capture_time = capture_time(frame_number);
  frame.frame_rate_hz = config_.rate_hz;
  const double t = time_s(frame_number);
  const std::uint64_t seed = config_.seed;
  frame.bodies.reserve(config_.bodies);
  for (std::size_t i = 0; i < config_.bodies; ++i) {
    if (absent(i, frame_number)) continue;
    core::BodySample body;
    body.name = body_name(i);
    body.tracked = !occluded(i, frame_number);
    if (body.tracked) {
      const BodyTruth truth_i = truth(i, t);
      body.p_world_m = truth_i.p_world_m;
      body.q_world_body = truth_i.q_world_body;
      if (config_.noise_mm > 0.0) {
        body.p_world_m += 1e-3 * config_.noise_mm * gaussian3(seed, frame_number, i, Draw::noise_p);
      }
      if (config_.noise_deg > 0.0) {
        const Eigen::Vector3d rotation_rad = config_.noise_deg * std::numbers::pi / 180.0 *
                                             gaussian3(seed, frame_number, i, Draw::noise_q);
        body.q_world_body =
            canonical(body.q_world_body * Eigen::Quaterniond(Eigen::AngleAxisd(
                                              rotation_rad.norm(), rotation_rad.normalized())));
      }
      if (config_.outliers > 0.0 &&
          uniform(seed, frame_number, i, Draw::outlier) < config_.outliers) {
        body.p_world_m += config_.outlier_m *
                          gaussian3(seed, frame_number, i, Draw::outlier_direction).normalized();
      }
    }
    frame.bodies.push_back(std::move(body));
  }
  return frame;
}

}  // namespace mocaplink::sources
