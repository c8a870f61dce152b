# MAVLink stream parser, single-frame parse and typed decode (libs/mavlink): every vehicle link.
mocaplink_fuzz(mavlink_stream ${CMAKE_CURRENT_SOURCE_DIR}/mavlink_stream.cpp mocaplink::mavlink)
