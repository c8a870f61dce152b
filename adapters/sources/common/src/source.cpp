#include "mocaplink/sources/source.hpp"
