# What a ground station may send through a `gcs` endpoint (issue 38): bytes → StreamParser →
# message_target → GcsRouter, in both directions, with vehicles attached and detached.
mocaplink_fuzz(gcs_router ${CMAKE_CURRENT_SOURCE_DIR}/gcs_router.cpp mocaplink::core)
