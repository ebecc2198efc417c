#include "nav/qrm/state_set.hpp"

#include <ostream>
#include <stdexcept>
#include <string>

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

void check_state(State s) {
  if (s < 1 || s > kStateCount) throw std::out_of_range("EDC state " + std::to_string(s) + " is not in 1..20");
}

}  // namespace neopipe::nav::qrm
