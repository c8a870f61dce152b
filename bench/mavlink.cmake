# MAVLink codec throughput (docs/performance.md "MAVLink codec"). Not a test: run by hand from a
# Release build, e.g. `build/<dir>/bench/mavlink_bench --benchmark_repetitions=5
# --benchmark_report_aggregates_only=true`.
add_executable(mavlink_bench ${CMAKE_CURRENT_SOURCE_DIR}/mavlink/mavlink_bench.cpp)
target_link_libraries(mavlink_bench PRIVATE mocaplink::mavlink benchmark::benchmark)
mocaplink_warnings(mavlink_bench)
set_target_properties(mavlink_bench PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/bench)
