# Recording CSV reader (replay://): libs/wire recording_csv.
mocaplink_fuzz(recording_csv ${CMAKE_CURRENT_SOURCE_DIR}/recording_csv.cpp mocaplink::wire)
