# Filter-accuracy harness (issue 3, docs/performance.md "Filter accuracy"). Not a test: run it by
# hand from a Release build, `build/<dir>/bench/filter_accuracy --csv build/filter.csv`.
add_executable(filter_accuracy
  ${CMAKE_CURRENT_SOURCE_DIR}/filter/main.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/filter/scenario.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/filter/estimators.cpp
  ${CMAKE_CURRENT_SOURCE_DIR}/filter/metrics.cpp)
target_link_libraries(filter_accuracy PRIVATE mocaplink::core)
mocaplink_warnings(filter_accuracy)
