# QTM RT packets (qtm:// client and emulator): framing, data packets with the 6DOF components,
# the mapping to MocapFrame, and the emulator's handling of client commands.
mocaplink_fuzz(qtm_rt ${CMAKE_CURRENT_SOURCE_DIR}/qtm_rt.cpp mocaplink::wire)
