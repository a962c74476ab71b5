#include "core/checksum.hpp"

#include "core/error.hpp"
#include "core/input_file.hpp"

#include <algorithm>
#include <cstdio>
#include <vector>

namespace lamina::core {

void Fnv1a::add(const void* data, std::size_t bytes) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < bytes; ++i) {
    h_ ^= p[i];
    h_ *= 0x100000001b3ULL;
  }
}

std::string Fnv1a::hex() const {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h_));
  return buf;
}

std::string fileChecksum(const std::filesystem::path& path, const std::string& what,
                         std::uint64_t from) {
  const InputFile in(path, what, kMaxHdf5Bytes);
  if (in.size() < from)
    throw Error("the " + what + " has " + std::to_string(in.size()) + " bytes, fewer than its " +
                    std::to_string(from) + "-byte header",
                {path.string(), 0, ""});
  Fnv1a f;
  std::vector<unsigned char> block(1u << 20);
  for (std::uint64_t offset = from; offset < in.size();) {
    const std::size_t n =
        static_cast<std::size_t>(std::min<std::uint64_t>(block.size(), in.size() - offset));
    in.readAt(offset, block.data(), n);
    f.add(block.data(), n);
    offset += n;
  }
  return "fnv1a64:" + f.hex();
}

} // namespace lamina::core
