#include "core/mesh/sides.h"

namespace facehex {

std::optional<Side> side_from_name(const std::string& name) {
  for (int s = 0; s < kNumSides; ++s)
    if (name == kSideNames[s]) return static_cast<Side>(s);
  return std::nullopt;
}

}  // namespace facehex
