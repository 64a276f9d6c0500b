// The position components a fix holds (clamp, prescribe), from the text of its
// `components` key: any of x, y, z, as dof_mask bits (src/simulation.hpp).
#pragma once

#include <string>

#include "params.hpp"
#include "simulation.hpp"

namespace slender {

inline int held_component_bits(const std::string& text, const std::string& who) {
  int bits = 0;
  for (char ch : text) {
    if (ch == 'x')
      bits |= kMaskX;
    else if (ch == 'y')
      bits |= kMaskY;
    else if (ch == 'z')
      bits |= kMaskZ;
    else
      throw InputError(who + ": components must use only x, y, z, got \"" + text + "\"");
  }
  return bits;
}

}  // namespace slender
