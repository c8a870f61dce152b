# bench/e2e: end-to-end throughput and latency of `mocaplink run` (sim:// → run → N UDP receivers).
# Not a test: run bench/e2e/run_e2e.sh $<TARGET_FILE:mocaplink> $<TARGET_FILE:e2e_receivers> and
# copy the table into docs/performance.md ("End to end").
add_executable(e2e_receivers ${CMAKE_CURRENT_SOURCE_DIR}/e2e/e2e_receivers.cpp)
mocaplink_warnings(e2e_receivers)
# The floor mocaplink is measured against (issue 15): the same source and loop hand-off, one
# pre-encoded datagram per vehicle, nothing else. run_e2e.sh runs both and prints the ratios.
add_executable(e2e_floor ${CMAKE_CURRENT_SOURCE_DIR}/e2e/e2e_floor.cpp)
target_link_libraries(e2e_floor PRIVATE mocaplink::core mocaplink::mavlink mocaplink::io
                      mocaplink::source_registry mocaplink_asio)
mocaplink_warnings(e2e_floor)
# The CPU cost of one loopback UDP send: plain, on a socket in epoll, as sendmmsg of one
# (docs/performance.md "Where the time goes").
add_executable(send_cost ${CMAKE_CURRENT_SOURCE_DIR}/e2e/send_cost.cpp)
mocaplink_warnings(send_cost)
