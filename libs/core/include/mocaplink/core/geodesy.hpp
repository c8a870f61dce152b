// Local NED <-> geodetic (WGS84) at the configured origin, through GeographicLib::LocalCartesian
// (DESIGN.md "Conventions"; docs/frames.md "Geodesy").
//
// The local frame is the tangent plane at the origin: N along the local meridian, E along the
// parallel, D along the ellipsoid normal (downwards). Altitude everywhere in this header is height
// above the WGS84 ellipsoid, in metres. The configured `[origin] altitude_m` is used as such; it is
// not converted from mean sea level (the geoid offset is the user's business: MAVLink's
// SET_GPS_GLOBAL_ORIGIN and HIL_GPS carry MSL altitude, see docs/messages.md for how builders fill
// those fields).
//
// Note that "north" of the local frame is the mocap axis chosen by the axis mapping; the origin
// makes it geographic north for the purpose of simulated GPS.
#pragma once

#include <memory>
#include <optional>

#include <Eigen/Core>

namespace GeographicLib {
class LocalCartesian;
}

namespace mocaplink::core {

/// A WGS84 geodetic position.
struct GeodeticPosition {
  double latitude_deg = 0.0;   ///< [-90, 90], positive north
  double longitude_deg = 0.0;  ///< [-180, 180), positive east (outputs are normalised to this)
  double altitude_m = 0.0;     ///< height above the WGS84 ellipsoid, metres
};

/// NED <-> ENU for any vector (position, velocity). The map swaps the first two components and
/// negates the third, so it is its own inverse: use it in both directions. The only place in the
/// code base where this conversion is written.
[[nodiscard]] Eigen::Vector3d ned_enu_swap(const Eigen::Vector3d& v);

/// The tangent-plane frame at a geodetic origin. Immutable; copies share one GeographicLib object.
/// Thread-safe for concurrent const use (GeographicLib::LocalCartesian's const methods are).
class LocalGeodeticFrame {
 public:
  /// Nullopt if the origin is not finite, |latitude| > 90 or |longitude| > 540 (GeographicLib's
  /// range). Longitudes outside [-180, 180) are normalised.
  [[nodiscard]] static std::optional<LocalGeodeticFrame> make(const GeodeticPosition& origin);

  /// The origin, longitude normalised to [-180, 180).
  [[nodiscard]] const GeodeticPosition& origin() const { return origin_; }

  /// Geodetic position of a local NED point (m). Exact (no small-distance approximation).
  [[nodiscard]] GeodeticPosition geodetic_from_ned(const Eigen::Vector3d& p_ned_m) const;

  /// Local NED point (m) of a geodetic position. Inverse of geodetic_from_ned.
  [[nodiscard]] Eigen::Vector3d ned_from_geodetic(const GeodeticPosition& position) const;

 private:
  LocalGeodeticFrame(const GeodeticPosition& origin,
                     std::shared_ptr<const GeographicLib::LocalCartesian> enu);
  GeodeticPosition origin_;
  std::shared_ptr<const GeographicLib::LocalCartesian> enu_;
};

}  // namespace mocaplink::core
