#include "pipeline/node.hpp"

namespace neopipe::pipeline {

void Node::begin_frame(NodeIO& io) {
  for (size_t k = 0; k < outputs_.size(); ++k) {
    if (is_image(outputs_[k].type)) io.out_image(k);
  }
}

}  // namespace neopipe::pipeline
