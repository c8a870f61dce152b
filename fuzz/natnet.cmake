# NatNet parsers: datagram framing, server info, connect, requests, model definitions and frames in
# every bitstream version, the body table and the mapping to MocapFrame, and the emulator's
# re-encoding of what was parsed.
mocaplink_fuzz(natnet ${CMAKE_CURRENT_SOURCE_DIR}/natnet.cpp mocaplink::wire)
