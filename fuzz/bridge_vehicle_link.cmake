# The Bridge's outside inputs: vehicle-link MAVLink bytes (StreamParser → decode → Bridge) and mocap
# poses with arbitrary values (core bridge, vehicle_state, sender, builders).
mocaplink_fuzz(bridge_vehicle_link ${CMAKE_CURRENT_SOURCE_DIR}/bridge_vehicle_link.cpp
               mocaplink::core)
