# VRPN client: cookie, message framing, sender/type descriptions, Pos_Quat and frame assembly.
mocaplink_fuzz(vrpn ${CMAKE_CURRENT_SOURCE_DIR}/vrpn.cpp mocaplink::wire)
