# bench/gcs_link: pose latency and ground-station traffic when a ground station shares the
# vehicle's serial link through mocaplink (issue 38, "poses first"). Not a test: run
# node bench/gcs_link/run_gcs_link.js --mocaplink $<TARGET_FILE:mocaplink> \
#   --relay $<TARGET_FILE:gcs_uart_relay> and copy the table into docs/performance.md.
# The relay emulates a UART between two ptys (baud/10 bytes/s each way, a 4 KiB driver buffer).
add_executable(gcs_uart_relay ${CMAKE_CURRENT_SOURCE_DIR}/gcs_link/uart_relay.cpp)
mocaplink_warnings(gcs_uart_relay)
