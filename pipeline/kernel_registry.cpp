#include "pipeline/kernel_registry.hpp"

#include "pipeline/nodes/nodes.hpp"

namespace neopipe::pipeline {

void KernelRegistry::add(KernelInfo info) {
  const std::string name = info.name;
  kernels_.insert_or_assign(name, std::move(info));
}

const KernelInfo* KernelRegistry::find(std::string_view name) const& {
  const auto it = kernels_.find(name);
  return it == kernels_.end() ? nullptr : &it->second;
}

std::vector<const KernelInfo*> KernelRegistry::all() const& {
  std::vector<const KernelInfo*> out;
  for (const auto& [name, info] : kernels_) out.push_back(&info);
  return out;
}

KernelRegistry standard_kernels() {
  KernelRegistry r;
  nodes::register_io_nodes(r);
  nodes::register_point_nodes(r);
  nodes::register_neighbourhood_nodes(r);
  nodes::register_symbolic_nodes(r);
  return r;
}

}  // namespace neopipe::pipeline
