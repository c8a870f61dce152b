# The Host header of every dashboard request (adapters/web http_auth: host_allowed, host_refusal),
# the DNS-rebinding check of issue 26.
if(TARGET mocaplink_web)
  mocaplink_fuzz(web_host_header ${CMAKE_CURRENT_SOURCE_DIR}/web_host_header.cpp
                 mocaplink::web nlohmann_json::nlohmann_json)
endif()
