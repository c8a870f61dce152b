// Anchors the config target until its sources land (issue 5). Delete when config.cpp exists.
namespace mocaplink::config {}
