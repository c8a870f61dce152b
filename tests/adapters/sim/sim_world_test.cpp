// SimWorld: determinism, ground truth vs. output, kinematic consistency, faults, config errors.
#include "mocaplink/sources/sim_world.hpp"

#include <cmath>
#include <numbers>
#include <string>
#include <variant>
#include <vector>

#include <gtest/gtest.h>

namespace mocaplink::sources {
namespace {

SimOptions noiseless(std::size_t bodies = 3) {
  SimOptions c;
  c.bodies = static_cast<std::uint32_t>(bodies);
  c.noise_mm = 0.0;
  c.noise_deg = 0.0;
  return c;
}

TEST(SimWorld, SameSeedGivesIdenticalFramesWhateverTheOrderOfRequests) {
  SimOptions c;
  c.seed = 42;
  c.occlude = 0.2;
  c.outliers = 0.05;
  const SimWorld a(c), b(c);
  // b is asked in reverse order: frames are a function of their number, not of history.
  for (std::uint64_t n = 400; n >= 1; --n) {
    const auto fa = a.frame(n), fb = b.frame(n);
    ASSERT_EQ(fa.frame_number, fb.frame_number);
    ASSERT_EQ(fa.capture_time, fb.capture_time);
    ASSERT_EQ(fa.bodies.size(), 3u);
    for (std::size_t i = 0; i < 3; ++i) {
      EXPECT_EQ(fa.bodies[i].name, fb.bodies[i].name);
      EXPECT_EQ(fa.bodies[i].tracked, fb.bodies[i].tracked);
      EXPECT_EQ(fa.bodies[i].p_world_m, fb.bodies[i].p_world_m);  // bit-identical
      EXPECT_EQ(fa.bodies[i].q_world_body.coeffs(), fb.bodies[i].q_world_body.coeffs());
    }
    EXPECT_EQ(a.dropped(n), b.dropped(n));
  }
}

TEST(SimWorld, DifferentSeedsGiveDifferentNoise) {
  SimOptions c1, c2;
  c2.seed = 2;
  const auto f1 = SimWorld(c1).frame(10), f2 = SimWorld(c2).frame(10);
  EXPECT_NE(f1.bodies[0].p_world_m, f2.bodies[0].p_world_m);
  // ...but the same underlying trajectory: the noise is sub-millimetre at noise_mm = 0.3.
  EXPECT_LT((f1.bodies[0].p_world_m - f2.bodies[0].p_world_m).norm(), 0.01);
}

TEST(SimWorld, NoiselessOutputIsTheGroundTruth) {
  const SimWorld world(noiseless(5));
  for (std::uint64_t n : {1ULL, 2ULL, 77ULL, 12345ULL}) {
    const auto frame = world.frame(n);
    const double t = static_cast<double>(n - 1) / 200.0;
    EXPECT_DOUBLE_EQ(world.time_s(n), t);
    EXPECT_EQ(frame.capture_time.time_since_epoch().count(), std::llround(t * 1e9));
    ASSERT_EQ(frame.bodies.size(), 5u);
    for (std::size_t i = 0; i < 5; ++i) {
      const auto truth = world.truth(i, t);
      EXPECT_EQ(frame.bodies[i].name, "Body" + std::to_string(i + 1));
      EXPECT_TRUE(frame.bodies[i].tracked);
      EXPECT_TRUE(frame.bodies[i].p_world_m.isApprox(truth.p_world_m, 1e-15));
      EXPECT_TRUE(
          frame.bodies[i].q_world_body.coeffs().isApprox(truth.q_world_body.coeffs(), 1e-15));
    }
  }
}

TEST(SimWorld, NoiseHasTheConfiguredStandardDeviation) {
  SimOptions c;
  c.noise_mm = 2.0;
  const SimWorld world(c);
  double sum_sq = 0.0;
  int count = 0;
  for (std::uint64_t n = 1; n <= 4000; ++n) {
    const auto frame = world.frame(n);
    const Eigen::Vector3d err =
        frame.bodies[1].p_world_m - world.truth(1, world.time_s(n)).p_world_m;
    sum_sq += err.squaredNorm();
    count += 3;
  }
  const double std_mm = 1e3 * std::sqrt(sum_sq / count);
  EXPECT_NEAR(std_mm, 2.0, 0.1);  // 12000 samples: relative standard error ~0.7 %
}

TEST(SimWorld, VelocityAndAccelerationAreTheDerivativesOfPosition) {
  const SimWorld world(noiseless(6));
  const double h = 1e-5;
  for (std::size_t i = 0; i < 6; ++i) {
    for (double t : {0.0, 0.37, 3.1, 17.25}) {
      const auto before = world.truth(i, t - h), at = world.truth(i, t),
                 after = world.truth(i, t + h);
      const Eigen::Vector3d v_fd = (after.p_world_m - before.p_world_m) / (2 * h);
      const Eigen::Vector3d a_fd = (after.v_world_m_s - before.v_world_m_s) / (2 * h);
      EXPECT_LT((v_fd - at.v_world_m_s).norm(), 1e-6) << "body " << i << " t " << t;
      EXPECT_LT((a_fd - at.a_world_m_s2).norm(), 1e-6) << "body " << i << " t " << t;
    }
  }
}

TEST(SimWorld, TrajectoriesAreDistinctAirborneAndSeparated) {
  const SimWorld world(noiseless(6));
  for (double t = 0.0; t < 30.0; t += 0.1) {
    for (std::size_t i = 0; i < 6; ++i) {
      const auto pi = world.truth(i, t);
      EXPECT_GT(pi.p_world_m.z(), 0.8);  // z is up: every body flies
      EXPECT_NEAR(pi.q_world_body.norm(), 1.0, 1e-12);
      EXPECT_GE(pi.q_world_body.w(), 0.0);
      for (std::size_t j = i + 1; j < 6; ++j) {
        EXPECT_GT((pi.p_world_m - world.truth(j, t).p_world_m).norm(), 0.3);
      }
    }
  }
  // Body2 flies a 1 m circle starting at angle 0 (x = centre + 1): its horizontal distance from
  // the centre is constant.
  double min_r = 1e9, max_r = 0.0;
  const Eigen::Vector2d c2(world.truth(1, 0.0).p_world_m.x() - 1.0, 0.0);
  for (double t = 0.0; t < 8.0; t += 0.05) {
    const Eigen::Vector2d xy = world.truth(1, t).p_world_m.head<2>() - c2;
    min_r = std::min(min_r, xy.norm());
    max_r = std::max(max_r, xy.norm());
  }
  EXPECT_NEAR(min_r, 1.0, 1e-9);
  EXPECT_NEAR(max_r, 1.0, 1e-9);
}

TEST(SimWorld, MovingBodiesPointTheirNoseAlongTheVelocity) {
  const SimWorld world(noiseless(3));
  for (std::size_t i : {1u, 2u}) {
    for (double t : {0.5, 2.0, 5.5}) {
      const auto truth = world.truth(i, t);
      const Eigen::Vector3d nose = truth.q_world_body * Eigen::Vector3d::UnitX();
      const Eigen::Vector2d v = truth.v_world_m_s.head<2>().normalized();
      EXPECT_GT(nose.head<2>().normalized().dot(v), 0.999) << "body " << i << " t " << t;
      // Tilt stays small: thrust axis within 15 degrees of vertical for these gentle paths.
      EXPECT_GT((truth.q_world_body * Eigen::Vector3d::UnitZ()).z(),
                std::cos(15.0 * std::numbers::pi / 180));
    }
  }
}

TEST(SimWorld, DropsOcclusionsAndOutliersFollowTheirProbabilities) {
  SimOptions c = noiseless(4);
  c.drop = 0.1;
  c.occlude = 0.25;
  c.occlude_s = 0.1;  // 20 frames per slot at 200 Hz
  c.outliers = 0.02;
  c.outlier_m = 0.5;
  const SimWorld world(c);
  int dropped = 0, occluded = 0, outliers = 0, tracked = 0;
  const int frames = 20000;
  for (std::uint64_t n = 1; n <= frames; ++n) {
    dropped += world.dropped(n) ? 1 : 0;
    const auto frame = world.frame(n);
    for (std::size_t i = 0; i < 4; ++i) {
      const auto& b = frame.bodies[i];
      if (!b.tracked) {
        ++occluded;
        continue;
      }
      ++tracked;
      const double err = (b.p_world_m - world.truth(i, world.time_s(n)).p_world_m).norm();
      if (err > 1e-9) {
        EXPECT_NEAR(err, 0.5, 1e-9);
        ++outliers;
      }
    }
  }
  EXPECT_NEAR(dropped / double(frames), 0.1, 0.01);
  EXPECT_NEAR(occluded / (4.0 * frames), 0.25, 0.05);  // 4000 slots: coarser
  EXPECT_NEAR(outliers / double(tracked), 0.02, 0.005);
  // Occlusions are whole slots: frames 1..20 share one slot.
  for (std::size_t i = 0; i < 4; ++i) {
    for (std::uint64_t n = 2; n <= 20; ++n) EXPECT_EQ(world.occluded(i, n), world.occluded(i, 1));
  }
}

TEST(SimOptions, GuardRefusesConfigsOutsideTheDocumentedRanges) {
  // URLs are range-checked by parse_sim_options; this guard is for options built in code.
  EXPECT_EQ(validate_sim_options(SimOptions{}), "");
  SimOptions c;
  c.bodies = 0;
  EXPECT_NE(validate_sim_options(c).find("bodies must be"), std::string::npos);
  c = SimOptions{};
  c.rate_hz = 0.0;
  EXPECT_NE(validate_sim_options(c).find("rate_hz must be"), std::string::npos);
  c = SimOptions{};
  c.drop = 1.0;
  EXPECT_NE(validate_sim_options(c).find("drop must be"), std::string::npos);
}

TEST(SimWorld, ChurnTakesTheLastBodyOutOfTheListInEveryOddSlot) {
  SimOptions c = noiseless(3);
  c.churn_s = 0.5;  // 100 frames per slot at 200 Hz; frame n is at t = (n - 1) / 200 s
  const SimWorld world(c);
  const auto names = [&world](std::uint64_t n) {
    std::vector<std::string> out;
    for (const auto& b : world.frame(n).bodies) out.push_back(b.name);
    return out;
  };
  const std::vector<std::string> all{"Body1", "Body2", "Body3"};
  const std::vector<std::string> two{"Body1", "Body2"};
  EXPECT_EQ(names(1), all);    // t = 0
  EXPECT_EQ(names(100), all);  // t = 0.495
  EXPECT_EQ(names(101), two);  // t = 0.5: gone
  EXPECT_EQ(names(200), two);
  EXPECT_EQ(names(201), all);  // t = 1.0: back
  EXPECT_EQ(names(301), two);
  c.churn_s = 0.0;
  const SimWorld steady(c);
  EXPECT_EQ(steady.frame(101).bodies.size(), 3U);
}

}  // namespace
}  // namespace mocaplink::sources
