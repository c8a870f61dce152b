// Geodesy against an independent oracle: PROJ's cct (Debian proj-bin) with a topocentric pipeline
// (geodetic -> geocentric "cart" -> local ENU "topocentric" -> NED by PROJ's own "axisswap"
// +order=2,1,-3), forward and inverse, at several origins. Both sides speak NED: our NED↔ENU swap
// is never applied to PROJ's numbers, so a wrong swap on our side shows up as a disagreement.
// Agreement must be better than 1 mm for points within 1 km. Starts cct processes, hence the
// conformance label; MOCAPLINK_CCT is the path CMake's find_program found.
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "mocaplink/core/geodesy.hpp"

#ifndef MOCAPLINK_CCT
#error "MOCAPLINK_CCT must be defined by CMake"
#endif

namespace mocaplink::core {
namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;
constexpr double kA = 6378137.0;
constexpr double kE2 = (1.0 / 298.257223563) * (2.0 - 1.0 / 298.257223563);
constexpr double kToleranceM = 1e-3;

// Runs cct on one line per point; returns the first three numbers of every output line.
std::vector<Eigen::Vector3d> run_cct(const GeodeticPosition& o, bool inverse,
                                     const std::vector<Eigen::Vector3d>& in) {
  std::ostringstream cmd;
  cmd.precision(15);
  cmd << "printf '%b' '";
  for (const auto& p : in) cmd << p.x() << ' ' << p.y() << ' ' << p.z() << "\\n";
  cmd << "' | '" << MOCAPLINK_CCT << "' -d 12" << (inverse ? " -I" : "")
      << " +proj=pipeline +step +proj=cart +ellps=WGS84 +step +proj=topocentric +ellps=WGS84"
      << " +lat_0=" << o.latitude_deg << " +lon_0=" << o.longitude_deg << " +h_0=" << o.altitude_m
      << " +step +proj=axisswap +order=2,1,-3";  // E N U -> N E D
  std::vector<Eigen::Vector3d> out;
  FILE* pipe = popen(cmd.str().c_str(), "r");
  if (pipe == nullptr) return out;
  std::array<char, 512> line{};
  while (std::fgets(line.data(), static_cast<int>(line.size()), pipe) != nullptr) {
    std::istringstream fields(line.data());
    Eigen::Vector3d v;
    if (fields >> v.x() >> v.y() >> v.z()) out.push_back(v);
  }
  pclose(pipe);
  return out;
}

// Geodetic difference in metres (north, east, up) using the local radii of curvature: exact
// enough for sub-millimetre differences.
double metres_between(const GeodeticPosition& a, const GeodeticPosition& b) {
  const double lat = a.latitude_deg * kDegToRad;
  const double w = std::sqrt(1.0 - kE2 * std::sin(lat) * std::sin(lat));
  const double n_radius = kA / w;
  const double m_radius = kA * (1.0 - kE2) / (w * w * w);
  double dlon = b.longitude_deg - a.longitude_deg;
  dlon -= 360.0 * std::round(dlon / 360.0);  // across the antimeridian
  const double dn = (b.latitude_deg - a.latitude_deg) * kDegToRad * (m_radius + a.altitude_m);
  const double de = dlon * kDegToRad * (n_radius + a.altitude_m) * std::cos(lat);
  const double du = b.altitude_m - a.altitude_m;
  return std::sqrt(dn * dn + de * de + du * du);
}

struct Origin {
  const char* name;
  GeodeticPosition position;
};

class GeodesyVsCct : public ::testing::TestWithParam<Origin> {};

// Points within 1 km of the origin (NED, m), including the corners of a 1 km cube's diagonal.
const std::vector<Eigen::Vector3d> kNedPoints = {
    {0, 0, 0},        {1000, 0, 0},         {0, 1000, 0},         {-1000, 0, 0},
    {0, -1000, 0},    {0, 0, -1000},        {0, 0, 1000},         {-577, 577, -577},
    {577, -577, 577}, {0.123, -4.56, -1.2}, {350.5, 820.25, -30}, {-999.9, 10, 2}};

TEST_P(GeodesyVsCct, NedToGeodeticMatchesInversePipeline) {
  ASSERT_STRNE(MOCAPLINK_CCT, "MOCAPLINK_CCT-NOTFOUND") << "install proj-bin (scripts/setup)";
  const Origin& origin = GetParam();
  const auto frame = LocalGeodeticFrame::make(origin.position);
  ASSERT_TRUE(frame.has_value());
  const auto cct = run_cct(origin.position, true, kNedPoints);  // N E D in, lon lat h out
  ASSERT_EQ(cct.size(), kNedPoints.size());
  for (std::size_t i = 0; i < kNedPoints.size(); ++i) {
    const GeodeticPosition ours = frame->geodetic_from_ned(kNedPoints[i]);
    const GeodeticPosition theirs{cct[i].y(), cct[i].x(), cct[i].z()};
    EXPECT_LT(metres_between(theirs, ours), kToleranceM)
        << origin.name << " point " << kNedPoints[i].transpose() << ": ours " << ours.latitude_deg
        << " " << ours.longitude_deg << " " << ours.altitude_m << ", cct " << theirs.latitude_deg
        << " " << theirs.longitude_deg << " " << theirs.altitude_m;
    EXPECT_GE(ours.longitude_deg, -180.0);
    EXPECT_LT(ours.longitude_deg, 180.0);
  }
}

TEST_P(GeodesyVsCct, GeodeticToNedMatchesForwardPipeline) {
  ASSERT_STRNE(MOCAPLINK_CCT, "MOCAPLINK_CCT-NOTFOUND") << "install proj-bin (scripts/setup)";
  const Origin& origin = GetParam();
  const auto frame = LocalGeodeticFrame::make(origin.position);
  ASSERT_TRUE(frame.has_value());
  // Geodetic points a few hundred metres away, chosen in degrees (not produced by our code).
  const GeodeticPosition& o = origin.position;
  const double lat_step = 0.004;                                         // ~445 m
  const double lon_step = std::abs(o.latitude_deg) > 80 ? 0.05 : 0.005;  // < 1 km at 89 deg too
  std::vector<GeodeticPosition> points = {
      o,
      {o.latitude_deg + lat_step, o.longitude_deg, o.altitude_m + 10},
      {o.latitude_deg - lat_step, o.longitude_deg + lon_step, o.altitude_m - 3},
      {o.latitude_deg, o.longitude_deg - lon_step, o.altitude_m + 250},
      {o.latitude_deg + lat_step / 3, o.longitude_deg + lon_step, o.altitude_m}};
  std::vector<Eigen::Vector3d> lon_lat_h;
  for (const auto& p : points)
    lon_lat_h.emplace_back(p.longitude_deg, p.latitude_deg, p.altitude_m);
  const auto cct = run_cct(o, false, lon_lat_h);  // N E D
  ASSERT_EQ(cct.size(), points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d ours = frame->ned_from_geodetic(points[i]);
    EXPECT_LT((ours - cct[i]).norm(), kToleranceM)
        << origin.name << " point " << i << ": ours NED " << ours.transpose() << ", cct NED "
        << cct[i].transpose();
    EXPECT_LT(ours.norm(), 1100.0);  // the points really are local
  }
}

INSTANTIATE_TEST_SUITE_P(Origins, GeodesyVsCct,
                         ::testing::Values(Origin{"Urbana", {40.1156786, -88.2243507, 222.196}},
                                           Origin{"Sydney", {-33.8688, 151.2093, 58.0}},
                                           Origin{"Hobart", {-42.8821, 147.3272, -12.5}},
                                           Origin{"North89", {89.0, 12.5, 100.0}},
                                           Origin{"Antimeridian", {-16.5, 179.9999, 30.0}},
                                           Origin{"AntimeridianWest", {51.0, -179.9999, 0.0}},
                                           Origin{"NullIsland", {0.0, 0.0, 0.0}}),
                         [](const ::testing::TestParamInfo<Origin>& param_info) {
                           return std::string(param_info.param.name);
                         });

}  // namespace
}  // namespace mocaplink::core
