# QTM RT parameters XML (GetParameters answers): the bounded XML reader and the body-name rules.
mocaplink_fuzz(qtm_parameters ${CMAKE_CURRENT_SOURCE_DIR}/qtm_parameters.cpp mocaplink::wire)
