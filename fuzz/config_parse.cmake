# Configuration files and command-line overrides (libs/config): parse_config, --vehicle / --source /
# --http parsing, link URLs, and source URLs with every built-in source's option parser (registry).
mocaplink_fuzz(config_parse ${CMAKE_CURRENT_SOURCE_DIR}/config_parse.cpp mocaplink::config
               mocaplink::source_registry)
