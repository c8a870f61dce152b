# Dashboard request bodies (POST/PATCH /api/vehicles): adapters/web vehicle_request, then
# config::add_vehicle / update_vehicle as in the daemon.
if(TARGET mocaplink_web)
  mocaplink_fuzz(web_vehicle_request ${CMAKE_CURRENT_SOURCE_DIR}/web_vehicle_request.cpp
                 mocaplink::web mocaplink::config)
endif()
