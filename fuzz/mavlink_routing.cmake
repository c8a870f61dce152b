# message_target (libs/mavlink routing.hpp): the target fields of every frame a router forwards.
mocaplink_fuzz(mavlink_routing ${CMAKE_CURRENT_SOURCE_DIR}/mavlink_routing.cpp mocaplink::mavlink)
