# PX4's uXRCE-DDS samples the ros2:// link reads: VehicleOdometry and VehicleStatus (libs/wire
# px4_messages).
mocaplink_fuzz(px4_dds ${CMAKE_CURRENT_SOURCE_DIR}/px4_dds.cpp mocaplink::wire)
