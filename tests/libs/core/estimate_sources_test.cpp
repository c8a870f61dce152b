// Estimate sources (estimate_sources.hpp) against the parameter meanings of
// protocols/autopilots.md §8 (EK3_SRCn_* 6 = ExternalNav; EKF2_EV_CTRL bits 1 and 8;
// EKF2_AID_MASK bits 8 and 16 up to PX4 1.13).
#include "mocaplink/core/estimate_sources.hpp"

#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace mocaplink::core {
namespace {

ParameterLookup params(std::map<std::string, double> values) {
  return [values = std::move(values)](std::string_view name) -> std::optional<double> {
    const auto it = values.find(std::string(name));
    if (it == values.end()) return std::nullopt;
    return it->second;
  };
}

TEST(EstimateSources, ArduPilotExternalNavYawAndPositionAreMocaps) {
  const auto s = estimate_sources(AutopilotFamily::ardupilot, std::nullopt, SetupInput::vision,
                                  params({{"EK3_SRC1_YAW", 6}, {"EK3_SRC1_POSXY", 6}}));
  EXPECT_EQ(s.yaw, (QuantitySource{EstimateSource::mocap, "EK3_SRC1_YAW = 6"}));
  EXPECT_EQ(s.position, (QuantitySource{EstimateSource::mocap, "EK3_SRC1_POSXY = 6"}));
  EXPECT_EQ(describe_unchecked("yaw", s.yaw),
            "yaw not checkable: the vehicle's yaw comes from mocap (EK3_SRC1_YAW = 6)");
}

TEST(EstimateSources, ArduPilotCompassYawIsIndependent) {
  const auto s = estimate_sources(AutopilotFamily::ardupilot, std::nullopt, SetupInput::vision,
                                  params({{"EK3_SRC1_YAW", 1}, {"EK3_SRC1_POSXY", 6}}));
  EXPECT_EQ(s.yaw.source, EstimateSource::independent);
  EXPECT_EQ(s.position.source, EstimateSource::mocap);
  EXPECT_EQ(describe_unchecked("yaw", s.yaw), std::nullopt);
}

TEST(EstimateSources, ArduPilotGpsYawIsMocapsOnlyWhenTheGpsIsMocaplinks) {
  const auto lookup = params({{"EK3_SRC1_YAW", 2}, {"EK3_SRC1_POSXY", 3}});
  const auto fake =
      estimate_sources(AutopilotFamily::ardupilot, std::nullopt, SetupInput::fake_gps, lookup);
  EXPECT_EQ(fake.yaw.source, EstimateSource::mocap);  // GPS_INPUT carries our yaw
  EXPECT_EQ(fake.position.source, EstimateSource::mocap);
  const auto vision =
      estimate_sources(AutopilotFamily::ardupilot, std::nullopt, SetupInput::vision, lookup);
  EXPECT_EQ(vision.yaw.source, EstimateSource::independent);  // a real GPS of its own
  EXPECT_EQ(vision.position.source, EstimateSource::independent);
}

TEST(EstimateSources, UnreadParametersAreUnknownAndSaySo) {
  const auto s =
      estimate_sources(AutopilotFamily::ardupilot, std::nullopt, SetupInput::vision, params({}));
  EXPECT_EQ(s.yaw, (QuantitySource{EstimateSource::unknown, "EK3_SRC1_YAW"}));
  EXPECT_EQ(describe_unchecked("yaw", s.yaw),
            "yaw not checkable yet: EK3_SRC1_YAW not read from the vehicle (does its yaw come "
            "from mocap?)");
  const auto other = estimate_sources(AutopilotFamily::other, std::nullopt, SetupInput::vision,
                                      params({{"EK3_SRC1_YAW", 1}}));
  EXPECT_EQ(other.yaw.source, EstimateSource::unknown);
  EXPECT_EQ(describe_unchecked("position", other.position),
            "position not checkable: unknown whether the vehicle's position comes from mocap (no "
            "set-up rules for its autopilot)");
  // Before the first HEARTBEAT the autopilot is not known: "not yet", not "no rules".
  const auto unheard =
      estimate_sources(AutopilotFamily::unknown, std::nullopt, SetupInput::vision, params({}));
  EXPECT_EQ(unheard.heading.source, EstimateSource::unknown);
  EXPECT_EQ(describe_unchecked("yaw", unheard.yaw),
            "yaw not checkable yet: no HEARTBEAT from the vehicle yet (which autopilot says where "
            "its yaw comes from)");
  EXPECT_EQ(describe_unchecked(unheard, false),
            "yaw and position not checkable yet: no HEARTBEAT from the vehicle yet (which "
            "autopilot says where they come from)");
}

TEST(EstimateSources, ArduPilotsCompassIsAHeadingOfItsOwnOnceEnabledAndCalibrated) {
  // Issue 48: RAW_IMU carries the primary compass's field whenever COMPASS_ENABLE is set,
  // whether or not COMPASS_USE lets the EKF use it (4.5 send_raw_imu, Copter's update of the
  // compass); a compass is calibrated by ArduPilot's own test once its offsets are not all 0.
  const auto with = [](std::map<std::string, double> compass) {
    compass.emplace("EK3_SRC1_YAW", 6);
    compass.emplace("EK3_SRC1_POSXY", 6);
    return estimate_sources(AutopilotFamily::ardupilot, std::nullopt, SetupInput::vision,
                            params(std::move(compass)));
  };
  const std::map<std::string, double> calibrated{{"COMPASS_ENABLE", 1},
                                                 {"COMPASS_OFS_X", 5},
                                                 {"COMPASS_OFS_Y", 13},
                                                 {"COMPASS_OFS_Z", -18},
                                                 {"COMPASS_DEC", 0.2}};
  const auto in_use = with(calibrated);
  EXPECT_EQ(in_use.heading, (QuantitySource{EstimateSource::independent,
                                            "its compass in RAW_IMU: COMPASS_ENABLE = 1, "
                                            "calibrated"}));
  EXPECT_DOUBLE_EQ(in_use.declination_rad, 0.2);
  EXPECT_TRUE(checks_second_heading(in_use));
  EXPECT_EQ(describe_unchecked(in_use),
            "yaw compared with its compass only (its compass in RAW_IMU: COMPASS_ENABLE = 1, "
            "calibrated), 45° allowed: the vehicle's yaw comes from mocap (EK3_SRC1_YAW = 6); "
            "position not checkable: the vehicle's position comes from mocap (EK3_SRC1_POSXY = "
            "6)");
  // Wanted but not arrived: not claimed.
  EXPECT_EQ(describe_unchecked(in_use, false),
            "yaw not checkable: the vehicle's yaw comes from mocap (EK3_SRC1_YAW = 6); its compass "
            "heading (its compass in RAW_IMU: COMPASS_ENABLE = 1, calibrated) has not arrived: the "
            "nose is unchecked; position not checkable: the vehicle's position comes from mocap "
            "(EK3_SRC1_POSXY = 6)");
  // COMPASS_USE does not decide (ArduPilot's ExternalNav guides set it 0): not even read.
  auto unused = calibrated;
  unused.emplace("COMPASS_USE", 0);
  EXPECT_EQ(with(unused).heading, in_use.heading);
  // One offset not 0 is calibrated; all 0 is not, and an uncalibrated compass is no heading.
  auto one = calibrated;
  one["COMPASS_OFS_X"] = 0;
  one["COMPASS_OFS_Y"] = 0;
  EXPECT_EQ(with(one).heading.source, EstimateSource::independent);
  one["COMPASS_OFS_Z"] = 0;
  const auto raw = with(one);
  EXPECT_EQ(raw.heading, (QuantitySource{EstimateSource::none,
                                         "COMPASS_OFS_X, _Y and _Z = 0: its compass is not "
                                         "calibrated, so its field is no heading"}));
  EXPECT_FALSE(checks_second_heading(raw));
  EXPECT_EQ(describe_unchecked(with({{"COMPASS_ENABLE", 0}})),
            "yaw not checkable: the vehicle's yaw comes from mocap (EK3_SRC1_YAW = 6), and it has "
            "no heading of its own (COMPASS_ENABLE = 0: no compass): the nose is unchecked; "
            "position not checkable: the vehicle's position comes from mocap (EK3_SRC1_POSXY = "
            "6)");
  // Not read yet: unknown, naming the first missing; the declination alone is not waited for.
  const auto unread = with({{"COMPASS_ENABLE", 1}, {"COMPASS_OFS_X", 5}});
  EXPECT_EQ(unread.heading, (QuantitySource{EstimateSource::unknown, "COMPASS_OFS_Y"}));
  EXPECT_FALSE(checks_second_heading(unread));
  EXPECT_EQ(with({}).heading, (QuantitySource{EstimateSource::unknown, "COMPASS_ENABLE"}));
  auto no_declination = calibrated;
  no_declination.erase("COMPASS_DEC");
  EXPECT_EQ(with(no_declination).heading.source, EstimateSource::independent);
  EXPECT_DOUBLE_EQ(with(no_declination).declination_rad, 0.0);
  // A yaw of the vehicle's own (compass yaw) needs no second heading.
  auto own_yaw = calibrated;
  own_yaw.emplace("EK3_SRC1_YAW", 1);
  const auto compass_yaw = estimate_sources(AutopilotFamily::ardupilot, std::nullopt,
                                            SetupInput::vision, params(own_yaw));
  EXPECT_EQ(compass_yaw.heading.source, EstimateSource::none);
  EXPECT_FALSE(checks_second_heading(compass_yaw));
  EXPECT_EQ(std::vector<std::string_view>(source_parameters(AutopilotFamily::ardupilot).begin(),
                                          source_parameters(AutopilotFamily::ardupilot).end()),
            (std::vector<std::string_view>{"COMPASS_ENABLE", "COMPASS_OFS_X", "COMPASS_OFS_Y",
                                           "COMPASS_OFS_Z", "COMPASS_DEC"}));
  EXPECT_EQ(std::vector<std::string_view>(source_parameters(AutopilotFamily::px4).begin(),
                                          source_parameters(AutopilotFamily::px4).end()),
            (std::vector<std::string_view>{"SYS_HAS_MAG", "EKF2_MAG_DECL"}));
  EXPECT_TRUE(source_parameters(AutopilotFamily::other).empty());
}

TEST(EstimateSources, Px4WithVisionYawHasItsMagnetometerWhereItHasOne) {
  // PX4 publishes its magnetometer (HIGHRES_IMU) whenever SYS_HAS_MAG = 1, whatever EKF2 fuses.
  const FirmwareVersion v1_14{1, 14, 3, 0};
  const auto with_mag = estimate_sources(AutopilotFamily::px4, v1_14, SetupInput::vision,
                                         params({{"EKF2_EV_CTRL", 15}, {"SYS_HAS_MAG", 1}}));
  EXPECT_EQ(with_mag.heading, (QuantitySource{EstimateSource::independent,
                                              "the magnetometer in HIGHRES_IMU: SYS_HAS_MAG = 1"}));
  EXPECT_TRUE(checks_second_heading(with_mag));
  EXPECT_DOUBLE_EQ(with_mag.declination_rad, 0.0);  // EKF2_MAG_DECL not read: 0
  const auto declined =
      estimate_sources(AutopilotFamily::px4, v1_14, SetupInput::vision,
                       params({{"EKF2_EV_CTRL", 15}, {"SYS_HAS_MAG", 1}, {"EKF2_MAG_DECL", 90}}));
  EXPECT_NEAR(declined.declination_rad, 1.5707963267948966, 1e-15);  // degrees there
  const auto no_mag = estimate_sources(AutopilotFamily::px4, v1_14, SetupInput::vision,
                                       params({{"EKF2_EV_CTRL", 15}, {"SYS_HAS_MAG", 0}}));
  EXPECT_EQ(no_mag.heading.source, EstimateSource::none);
  EXPECT_NE(describe_unchecked(no_mag).value().find(
                "and it has no heading of its own (SYS_HAS_MAG = 0: no magnetometer): the nose is "
                "unchecked"),
            std::string::npos);
  const auto unread = estimate_sources(AutopilotFamily::px4, v1_14, SetupInput::vision,
                                       params({{"EKF2_EV_CTRL", 15}}));
  EXPECT_EQ(unread.heading, (QuantitySource{EstimateSource::unknown, "SYS_HAS_MAG"}));
  // Its own yaw (EKF2_EV_CTRL without bit 3) needs no second heading.
  const auto mag_yaw = estimate_sources(AutopilotFamily::px4, v1_14, SetupInput::vision,
                                        params({{"EKF2_EV_CTRL", 7}, {"SYS_HAS_MAG", 1}}));
  EXPECT_FALSE(checks_second_heading(mag_yaw));
  EXPECT_EQ(px4_dds_sources().heading.source, EstimateSource::none);
}

TEST(EstimateSources, Px4EvCtrlBits) {
  const FirmwareVersion v1_15{1, 15, 0, 0};
  // 15 = horizontal position 1 + vertical 2 + velocity 4 + yaw 8.
  auto s = estimate_sources(AutopilotFamily::px4, v1_15, SetupInput::vision,
                            params({{"EKF2_EV_CTRL", 15}}));
  EXPECT_EQ(s.yaw, (QuantitySource{EstimateSource::mocap, "EKF2_EV_CTRL = 15"}));
  EXPECT_EQ(s.position.source, EstimateSource::mocap);
  // 7: no EV yaw (the magnetometer's heading).
  s = estimate_sources(AutopilotFamily::px4, v1_15, SetupInput::vision,
                       params({{"EKF2_EV_CTRL", 7}}));
  EXPECT_EQ(s.yaw.source, EstimateSource::independent);
  EXPECT_EQ(s.position.source, EstimateSource::mocap);
  // 1.13: EKF2_AID_MASK 24 = vision position 8 + vision yaw 16; EKF2_EV_CTRL is not its name.
  s = estimate_sources(AutopilotFamily::px4, FirmwareVersion{1, 13, 3, 0}, SetupInput::vision,
                       params({{"EKF2_AID_MASK", 8}, {"EKF2_EV_CTRL", 15}}));
  EXPECT_EQ(s.yaw, (QuantitySource{EstimateSource::independent, "EKF2_AID_MASK = 8"}));
  EXPECT_EQ(s.position.source, EstimateSource::mocap);
}

TEST(EstimateSources, Px4HilGpsPositionIsMocapsAndItsYawIsTheCompass) {
  const auto s =
      estimate_sources(AutopilotFamily::px4, std::nullopt, SetupInput::fake_gps, params({}));
  EXPECT_EQ(s.position.source, EstimateSource::mocap);
  EXPECT_EQ(s.yaw.source, EstimateSource::independent);
}

}  // namespace
}  // namespace mocaplink::core
