# Per-frame CPU cost of the core (docs/performance.md "Per-frame cost"): Bridge::on_frame with N
# vehicles. A plain harness (no Google Benchmark), so it also builds for the cross targets. Not a
# test: run by hand from a Release build, `build/<dir>/bench/bridge_cost`.
add_executable(bridge_cost ${CMAKE_CURRENT_SOURCE_DIR}/bridge/bridge_cost.cpp)
target_link_libraries(bridge_cost PRIVATE mocaplink::core)
mocaplink_warnings(bridge_cost)
set_target_properties(bridge_cost PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/bench)
