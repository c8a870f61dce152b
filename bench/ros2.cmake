# bench/ros2: capture → ROS 2 subscriber latency of `mocaplink run`'s [ros2] topics against a floor
# (issue 46). Not a test: run bench/ros2/run_ros2.sh (it names its binaries) and copy the table into
# docs/performance.md ("ROS 2 topics beside the vehicles").
if(MOCAPLINK_ROS2)
  # The floor writes through adapters/ros2's own DDS seam (src/dds.hpp), so that the two differ by
  # what mocaplink does per frame, not by the DDS writer.
  add_executable(ros2_floor ${CMAKE_CURRENT_SOURCE_DIR}/ros2/ros2_floor.cpp)
  target_link_libraries(ros2_floor PRIVATE mocaplink::ros2 mocaplink::core mocaplink::wire
                        mocaplink::io mocaplink::source_registry Threads::Threads)
  mocaplink_warnings(ros2_floor)
endif()
