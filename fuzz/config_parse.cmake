# Configuration files and command-line overrides (libs/config): parse_config, --vehicle / --source /
# --http parsing, link and source URLs.
mocaplink_fuzz(config_parse ${CMAKE_CURRENT_SOURCE_DIR}/config_parse.cpp mocaplink::config)
