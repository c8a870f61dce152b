#include "mocaplink/core/geodesy.hpp"

#include <cmath>
#include <utility>

#include <GeographicLib/LocalCartesian.hpp>

namespace mocaplink::core {
namespace {

// Longitude into [-180, 180).
double normalised_longitude(double lon_deg) {
  double out = std::fmod(lon_deg + 180.0, 360.0);
  if (out < 0.0) out += 360.0;
  return out - 180.0;
}

}  // namespace

Eigen::Vector3d ned_enu_swap(const Eigen::Vector3d& v) {
  // (N, E, D) -> (E, N, U) = (E, N, -D); applied to (E, N, U) it gives back (N, E, -U) = (N, E, D).
  return {v.y(), v.x(), -v.z()};
}

LocalGeodeticFrame::LocalGeodeticFrame(const GeodeticPosition& origin,
                                       std::shared_ptr<const GeographicLib::LocalCartesian> enu)
    : origin_(origin), enu_(std::move(enu)) {}

std::optional<LocalGeodeticFrame> LocalGeodeticFrame::make(const GeodeticPosition& origin) {
  if (!std::isfinite(origin.latitude_deg) || !std::isfinite(origin.longitude_deg) ||
      !std::isfinite(origin.altitude_m) || std::abs(origin.latitude_deg) > 90.0 ||
      std::abs(origin.longitude_deg) > 540.0) {
    return std::nullopt;
  }
  GeodeticPosition o = origin;
  o.longitude_deg = normalised_longitude(origin.longitude_deg);
  auto enu = std::make_shared<const GeographicLib::LocalCartesian>(
      o.latitude_deg, o.longitude_deg, o.altitude_m, GeographicLib::Geocentric::WGS84());
  return LocalGeodeticFrame(o, std::move(enu));
}

GeodeticPosition LocalGeodeticFrame::geodetic_from_ned(const Eigen::Vector3d& p_ned_m) const {
  const Eigen::Vector3d enu = ned_enu_swap(p_ned_m);
  GeodeticPosition out;
  enu_->Reverse(enu.x(), enu.y(), enu.z(), out.latitude_deg, out.longitude_deg, out.altitude_m);
  out.longitude_deg = normalised_longitude(out.longitude_deg);
  return out;
}

Eigen::Vector3d LocalGeodeticFrame::ned_from_geodetic(const GeodeticPosition& position) const {
  Eigen::Vector3d enu;
  enu_->Forward(position.latitude_deg, position.longitude_deg, position.altitude_m, enu.x(),
                enu.y(), enu.z());
  return ned_enu_swap(enu);
}

}  // namespace mocaplink::core
