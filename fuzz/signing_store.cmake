# Signing timestamp state files (adapters/io signing_store): read back at every start.
if(TARGET mocaplink_io)
  mocaplink_fuzz(signing_store ${CMAKE_CURRENT_SOURCE_DIR}/signing_store.cpp mocaplink::io)
endif()
