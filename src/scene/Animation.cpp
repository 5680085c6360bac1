#include "scene/Animation.h"

namespace obscura {}  // namespace obscura
