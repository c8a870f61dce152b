# DataStream parser: packet framing, every item the client reads, the §7 caches and the mapping to
# MocapFrame; also the emulator's handling of client packets.
mocaplink_fuzz(vicon_datastream ${CMAKE_CURRENT_SOURCE_DIR}/vicon_datastream.cpp mocaplink::wire)
