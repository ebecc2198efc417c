#pragma once
// Registration of the standard kernels, one family per file.

#include "pipeline/kernel_registry.hpp"

namespace neopipe::pipeline::nodes {

void register_io_nodes(KernelRegistry& r);             // source, image
void register_point_nodes(KernelRegistry& r);          // gray, lut, threshold, ALU ops, lut2, convert
void register_neighbourhood_nodes(KernelRegistry& r);  // conv3x3, bool3x3
void register_symbolic_nodes(KernelRegistry& r);       // histogram, blobs, value_blobs

/// The kernel name of the graph's frame source node.
inline constexpr const char* kSourceKernel = "source";

}  // namespace neopipe::pipeline::nodes
