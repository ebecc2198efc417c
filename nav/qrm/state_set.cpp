#include "nav/qrm/state_set.hpp"

#include <ostream>

namespace neopipe::nav::qrm {

std::string StateSet::to_string() const {
  std::string text = "{";
  for (const State s : *this) {
    if (text.size() > 1) text += ',';
    text += std::to_string(s);
  }
  return text + '}';
}

std::ostream& operator<<(std::ostream& out, StateSet set) {
  return out << set.to_string();
}

}  // namespace neopipe::nav::qrm
