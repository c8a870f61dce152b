// time.hpp is header-only; this file anchors the core target until it has its own sources.
#include "mocaplink/core/time.hpp"
