#include "batch/checksum.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <vector>

namespace neopipe::batch {
namespace {

constexpr std::uint64_t kFnvPrime = 0x100000001b3ULL;

std::uint64_t mix_word(std::uint64_t state, std::uint64_t word) {
  state ^= word;
  state *= kFnvPrime;
  return state ^ (state >> 32);
}

std::uint64_t little_endian_word(const unsigned char* p) {
  std::uint64_t w = 0;
  for (int i = 7; i >= 0; --i) w = (w << 8) | p[i];
  return w;
}

}  // namespace

void Checksum::update(std::span<const unsigned char> bytes) {
  length_ += bytes.size();
  std::size_t at = 0;
  while (tail_size_ > 0 && tail_size_ < 8 && at < bytes.size()) tail_[tail_size_++] = bytes[at++];
  if (tail_size_ == 8) {
    state_ = mix_word(state_, little_endian_word(tail_));
    tail_size_ = 0;
  }
  for (; at + 8 <= bytes.size(); at += 8) state_ = mix_word(state_, little_endian_word(bytes.data() + at));
  while (at < bytes.size()) tail_[tail_size_++] = bytes[at++];
}

std::uint64_t Checksum::value() const {
  std::uint64_t s = state_;
  for (std::size_t i = 0; i < tail_size_; ++i) s = mix_word(s, tail_[i]);
  s = mix_word(s, length_);
  // A final avalanche (MurmurHash3's fmix64), so that nearby inputs give unrelated digests.
  s ^= s >> 33;
  s *= 0xff51afd7ed558ccdULL;
  s ^= s >> 33;
  s *= 0xc4ceb9fe1a85ec53ULL;
  s ^= s >> 33;
  return s;
}

std::string file_checksum(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot open: {}", path.string(), std::strerror(errno)));
  Checksum c;
  std::vector<char> buffer(1 << 20);
  while (in) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    const auto got = static_cast<std::size_t>(in.gcount());
    c.update({reinterpret_cast<const unsigned char*>(buffer.data()), got});
  }
  if (in.bad()) throw std::runtime_error(fmt::format("{}: read failed", path.string()));
  return fmt::format("{:016x}", c.value());
}

std::string text_checksum(const std::string& text) {
  Checksum c;
  c.update({reinterpret_cast<const unsigned char*>(text.data()), text.size()});
  return fmt::format("{:016x}", c.value());
}

}  // namespace neopipe::batch
