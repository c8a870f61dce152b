// Geodesy against hand-derived values (docs/frames.md "Geodesy"). The PROJ oracle comparison is in
// geodesy_conformance_test.cpp.
#include "mocaplink/core/geodesy.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include <gtest/gtest.h>

namespace mocaplink::core {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kA = 6378137.0;            // WGS84 semi-major axis, m
constexpr double kF = 1.0 / 298.257223563;  // WGS84 flattening
constexpr double kE2 = kF * (2.0 - kF);     // first eccentricity squared
constexpr double kRadToDeg = 180.0 / std::numbers::pi;

LocalGeodeticFrame frame_at(double lat, double lon, double alt) {
  auto f = LocalGeodeticFrame::make({lat, lon, alt});
  EXPECT_TRUE(f.has_value());
  return *f;
}

TEST(NedEnuSwap, SwapsAndNegatesAndIsItsOwnInverse) {
  const Eigen::Vector3d enu = ned_enu_swap({1, 2, 3});
  EXPECT_EQ(enu, Eigen::Vector3d(2, 1, -3));
  EXPECT_EQ(ned_enu_swap(enu), Eigen::Vector3d(1, 2, 3));
  // -0 and 0 survive the round trip.
  const Eigen::Vector3d z = ned_enu_swap(ned_enu_swap({0.0, -0.0, 0.0}));
  EXPECT_FALSE(std::signbit(z.x()));
  EXPECT_TRUE(std::signbit(z.y()));
}

TEST(LocalGeodeticFrame, RejectsBadOrigins) {
  EXPECT_FALSE(LocalGeodeticFrame::make({kNaN, 0, 0}).has_value());
  EXPECT_FALSE(LocalGeodeticFrame::make({0, kNaN, 0}).has_value());
  EXPECT_FALSE(LocalGeodeticFrame::make({0, 0, kNaN}).has_value());
  EXPECT_FALSE(LocalGeodeticFrame::make({90.0001, 0, 0}).has_value());
  EXPECT_FALSE(LocalGeodeticFrame::make({-91, 0, 0}).has_value());
  EXPECT_FALSE(LocalGeodeticFrame::make({0, 540.5, 0}).has_value());
  EXPECT_TRUE(LocalGeodeticFrame::make({90, 0, 0}).has_value());
  EXPECT_TRUE(LocalGeodeticFrame::make({-90, -180, -400}).has_value());
}

TEST(LocalGeodeticFrame, NormalisesOriginLongitude) {
  EXPECT_DOUBLE_EQ(frame_at(10, 190, 0).origin().longitude_deg, -170.0);
  EXPECT_DOUBLE_EQ(frame_at(10, -190, 0).origin().longitude_deg, 170.0);
  EXPECT_DOUBLE_EQ(frame_at(10, 180, 0).origin().longitude_deg, -180.0);
}

TEST(LocalGeodeticFrame, OriginAndStraightUp) {
  const auto f = frame_at(40.1156786, -88.2243507, 222.196);
  const GeodeticPosition o = f.geodetic_from_ned({0, 0, 0});
  EXPECT_NEAR(o.latitude_deg, 40.1156786, 1e-12);
  EXPECT_NEAR(o.longitude_deg, -88.2243507, 1e-12);
  EXPECT_NEAR(o.altitude_m, 222.196, 1e-8);
  // 10 m up along the ellipsoid normal: same latitude/longitude, altitude + 10.
  const GeodeticPosition up = f.geodetic_from_ned({0, 0, -10});
  EXPECT_NEAR(up.latitude_deg, 40.1156786, 1e-12);
  EXPECT_NEAR(up.longitude_deg, -88.2243507, 1e-12);
  EXPECT_NEAR(up.altitude_m, 232.196, 1e-8);
}

TEST(LocalGeodeticFrame, EquatorEastIsACircleOfRadiusA) {
  // The equator is a circle of radius a and the local normal there is radial, so 1000 m east on
  // the tangent plane is at longitude atan(1000 / a) and height sqrt(a^2 + 1000^2) - a, exactly.
  const auto f = frame_at(0, 0, 0);
  const GeodeticPosition p = f.geodetic_from_ned({0, 1000, 0});
  EXPECT_NEAR(p.latitude_deg, 0.0, 1e-12);
  EXPECT_NEAR(p.longitude_deg, std::atan(1000.0 / kA) * kRadToDeg, 1e-12);
  EXPECT_NEAR(p.altitude_m, std::hypot(kA, 1000.0) - kA, 1e-6);
}

TEST(LocalGeodeticFrame, EquatorNorthFollowsTheMeridianCurvature) {
  // Along the meridian at the equator the ellipse's radius of curvature is M = a (1 - e^2); over
  // 1 km the osculating circle is exact to far below a millimetre: lat = atan(d / M),
  // h = sqrt(M^2 + d^2) - M.
  const double m = kA * (1.0 - kE2);
  const auto f = frame_at(0, 0, 0);
  const GeodeticPosition p = f.geodetic_from_ned({1000, 0, 0});
  EXPECT_NEAR(p.latitude_deg, std::atan(1000.0 / m) * kRadToDeg, 1e-9);
  EXPECT_NEAR(p.longitude_deg, 0.0, 1e-12);
  EXPECT_NEAR(p.altitude_m, std::hypot(m, 1000.0) - m, 1e-4);
  // Down is down: 5 m below the origin.
  EXPECT_NEAR(f.geodetic_from_ned({0, 0, 5}).altitude_m, -5.0, 1e-8);
}

TEST(LocalGeodeticFrame, WrapsAcrossTheAntimeridian) {
  const auto f = frame_at(0, 179.9999, 0);
  const GeodeticPosition p = f.geodetic_from_ned({0, 100, 0});
  // 100 m east at the equator is atan(100 / a) deg = 0.000898315 deg: past 180, reported negative.
  EXPECT_NEAR(p.longitude_deg, 179.9999 + std::atan(100.0 / kA) * kRadToDeg - 360.0, 1e-10);
  EXPECT_LT(p.longitude_deg, -179.999);
  // And back.
  const Eigen::Vector3d ned = f.ned_from_geodetic(p);
  EXPECT_NEAR((ned - Eigen::Vector3d(0, 100, 0)).norm(), 0.0, 1e-8);
}

TEST(LocalGeodeticFrame, DocsFramesWorkedExample) {
  // docs/frames.md "Worked example": NED (1.2345, 0.6789, -1.5) m at the Urbana origin. Oracle
  // (PROJ 9.1.1): echo "0.6789 1.2345 1.5" | cct -d 12 -I +proj=pipeline +step +proj=cart
  // +ellps=WGS84 +step +proj=topocentric +ellps=WGS84 +lat_0=40.1156786 +lon_0=-88.2243507
  // +h_0=222.196   ->   -88.224342736602  40.115689717539  223.696000155061
  const auto f = frame_at(40.1156786, -88.2243507, 222.196);
  const GeodeticPosition p = f.geodetic_from_ned({1.2345, 0.6789, -1.5});
  EXPECT_NEAR(p.latitude_deg, 40.115689717539, 1e-11);
  EXPECT_NEAR(p.longitude_deg, -88.224342736602, 1e-11);
  EXPECT_NEAR(p.altitude_m, 223.696000155061, 1e-6);
}

TEST(LocalGeodeticFrame, RoundTripsEverywhere) {
  for (const auto& o : {GeodeticPosition{40.1156786, -88.2243507, 222.196},
                        GeodeticPosition{-33.8688, 151.2093, 58}, GeodeticPosition{89, 10, 0},
                        GeodeticPosition{-89.999, -45, 2800}, GeodeticPosition{0, 179.9999, 0}}) {
    const auto f = frame_at(o.latitude_deg, o.longitude_deg, o.altitude_m);
    for (const Eigen::Vector3d& p :
         {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1000, -20, 3), Eigen::Vector3d(-577, 577, -577),
          Eigen::Vector3d(0.001, 0.002, -0.003)}) {
      const Eigen::Vector3d back = f.ned_from_geodetic(f.geodetic_from_ned(p));
      EXPECT_NEAR((back - p).norm(), 0.0, 1e-8) << o.latitude_deg << " " << p.transpose();
    }
  }
}

}  // namespace
}  // namespace mocaplink::core
