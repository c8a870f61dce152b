# How late the vrpn:// client delivers each round when trackers report at unequal rates (issue 27,
# docs/sources.md "vrpn://"). Not a test: run it by hand, `build/<dir>/bench/vrpn_rounds`.
if(TARGET mocaplink_source_vrpn)
  add_executable(vrpn_rounds ${CMAKE_CURRENT_SOURCE_DIR}/vrpn_rounds/main.cpp)
  target_link_libraries(vrpn_rounds PRIVATE mocaplink::source_vrpn mocaplink::io Threads::Threads)
  mocaplink_warnings(vrpn_rounds)
endif()
