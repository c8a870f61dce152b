# Vicon Tracker UDP object stream: datagram parser and the stream (frame numbers, split frames,
# frozen objects, silence).
mocaplink_fuzz(vicon_udp ${CMAKE_CURRENT_SOURCE_DIR}/vicon_udp.cpp mocaplink::wire)
