// Estimate sources (estimate_sources.hpp) against the parameter meanings of
// protocols/autopilots.md §8 (EK3_SRCn_* 6 = ExternalNav; EKF2_EV_CTRL bits 1 and 8;
// EKF2_AID_MASK bits 8 and 16 up to PX4 1.13).
#include "mocaplink/core/estimate_sources.hpp"

#include <map>
#include <string>

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

TEST(EstimateSources, ArduPilotAhrs2IsAHeadingOfItsOwnOnlyWithTheCompassInUse) {
  // Issue 48: AHRS2 is DCM's attitude while EKF3 is active, and DCM corrects its yaw with the
  // compass when COMPASS_ENABLE and COMPASS_USE are set (AP_AHRS_DCM::use_compass, 4.5).
  const auto with = [](std::map<std::string, double> compass) {
    compass.emplace("EK3_SRC1_YAW", 6);
    compass.emplace("EK3_SRC1_POSXY", 6);
    return estimate_sources(AutopilotFamily::ardupilot, std::nullopt, SetupInput::vision,
                            params(std::move(compass)));
  };
  const auto in_use = with({{"COMPASS_ENABLE", 1}, {"COMPASS_USE", 1}});
  EXPECT_EQ(in_use.heading.source, EstimateSource::independent);
  EXPECT_TRUE(checks_second_heading(in_use));
  EXPECT_EQ(describe_unchecked(in_use),
            "yaw compared with its compass only (AHRS2, DCM with the compass: COMPASS_USE = 1), "
            "45° allowed: the vehicle's yaw comes from mocap (EK3_SRC1_YAW = 6); position not "
            "checkable: the vehicle's position comes from mocap (EK3_SRC1_POSXY = 6)");
  // Wanted but not arrived: not claimed.
  EXPECT_EQ(describe_unchecked(in_use, false),
            "yaw not checkable: the vehicle's yaw comes from mocap (EK3_SRC1_YAW = 6); its compass "
            "heading (AHRS2, DCM with the compass: COMPASS_USE = 1) has not arrived: the nose is "
            "unchecked; position not checkable: the vehicle's position comes from mocap "
            "(EK3_SRC1_POSXY = 6)");
  const auto unused = with({{"COMPASS_ENABLE", 1}, {"COMPASS_USE", 0}});
  EXPECT_EQ(unused.heading, (QuantitySource{EstimateSource::none,
                                            "COMPASS_USE = 0: AHRS2's yaw is the gyros' alone"}));
  EXPECT_FALSE(checks_second_heading(unused));
  EXPECT_EQ(describe_unchecked(unused),
            "yaw not checkable: the vehicle's yaw comes from mocap (EK3_SRC1_YAW = 6), and it has "
            "no heading of its own (COMPASS_USE = 0: AHRS2's yaw is the gyros' alone): the nose "
            "is unchecked; position not checkable: the vehicle's position comes from mocap "
            "(EK3_SRC1_POSXY = 6)");
  const auto disabled = with({{"COMPASS_ENABLE", 0}, {"COMPASS_USE", 1}});
  EXPECT_EQ(disabled.heading.source, EstimateSource::none);
  const auto unread = with({{"COMPASS_USE", 1}});
  EXPECT_EQ(unread.heading, (QuantitySource{EstimateSource::unknown, "COMPASS_ENABLE"}));
  EXPECT_FALSE(checks_second_heading(unread));
  // A yaw of the vehicle's own (compass yaw) needs no second heading.
  const auto compass_yaw =
      estimate_sources(AutopilotFamily::ardupilot, std::nullopt, SetupInput::vision,
                       params({{"EK3_SRC1_YAW", 1}, {"COMPASS_ENABLE", 1}, {"COMPASS_USE", 1}}));
  EXPECT_EQ(compass_yaw.heading.source, EstimateSource::none);
  EXPECT_FALSE(checks_second_heading(compass_yaw));
  ASSERT_EQ(source_parameters(AutopilotFamily::ardupilot).size(), 2U);
  EXPECT_EQ(source_parameters(AutopilotFamily::ardupilot)[1], "COMPASS_USE");
  ASSERT_EQ(source_parameters(AutopilotFamily::px4).size(), 1U);
  EXPECT_EQ(source_parameters(AutopilotFamily::px4)[0], "SYS_HAS_MAG");
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
