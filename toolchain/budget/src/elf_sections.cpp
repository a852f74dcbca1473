#include "kestrel/budget/elf_sections.hpp"

#include <fstream>
#include <iterator>

namespace kestrel::budget {
namespace {

constexpr uint32_t kShfWrite = 0x1;
constexpr uint32_t kShfAlloc = 0x2;
constexpr uint32_t kShfExecInstr = 0x4;
constexpr uint32_t kShtNobits = 8;

// Bounds-checked little-endian reads: a truncated file is an error, never a wild read.
class Reader {
 public:
  Reader(std::span<const uint8_t> b, const std::string& what) : bytes_(b), what_(what) {}
  uint64_t le(uint64_t offset, unsigned width) const {
    if (offset > bytes_.size() || width > bytes_.size() - offset) {
      throw BudgetError(what_ + ": truncated ELF (read of " + std::to_string(width) +
                        " bytes at offset " + std::to_string(offset) + ")");
    }
    uint64_t v = 0;
    for (unsigned i = 0; i < width; ++i) v |= uint64_t{bytes_[offset + i]} << (8 * i);
    return v;
  }

 private:
  std::span<const uint8_t> bytes_;
  const std::string& what_;
};

}  // namespace

ElfInfo parse_elf(std::span<const uint8_t> image, const std::string& what) {
  if (image.size() < 16 || image[0] != 0x7f || image[1] != 'E' || image[2] != 'L' ||
      image[3] != 'F') {
    throw BudgetError(what + ": not an ELF file");
  }
  if (image[4] != 1 && image[4] != 2) throw BudgetError(what + ": unknown ELF class");
  if (image[5] != 1) throw BudgetError(what + ": not a little-endian ELF file");
  ElfInfo info;
  info.is_64 = image[4] == 2;
  const Reader r(image, what);
  info.machine = static_cast<uint16_t>(r.le(18, 2));
  // Field offsets of the ELF header and of one section header, per class (ELF spec, gABI).
  const uint64_t shoff = info.is_64 ? r.le(0x28, 8) : r.le(0x20, 4);
  const uint64_t shentsize = r.le(info.is_64 ? 0x3A : 0x2E, 2);
  uint64_t shnum = r.le(info.is_64 ? 0x3C : 0x30, 2);
  if (shoff == 0) return info;  // no section table: nothing to count
  const uint64_t min_entsize = info.is_64 ? 64 : 40;
  if (shentsize < min_entsize) throw BudgetError(what + ": bad section header size");
  if (shnum == 0) shnum = info.is_64 ? r.le(shoff + 32, 8) : r.le(shoff + 20, 4);  // >= 0xff00
  if (shnum > image.size() / shentsize) throw BudgetError(what + ": bad section count");
  for (uint64_t i = 0; i < shnum; ++i) {
    const uint64_t sh = shoff + i * shentsize;
    const uint64_t type = r.le(sh + 4, 4);
    const uint64_t flags = info.is_64 ? r.le(sh + 8, 8) : r.le(sh + 8, 4);
    const uint64_t size = info.is_64 ? r.le(sh + 32, 8) : r.le(sh + 20, 4);
    if ((flags & kShfAlloc) == 0) continue;
    if (flags & kShfExecInstr) {
      info.sizes.code += size;
    } else if (type == kShtNobits) {
      info.sizes.bss += size;
    } else if (flags & kShfWrite) {
      info.sizes.data += size;
    } else {
      info.sizes.rodata += size;
    }
  }
  return info;
}

std::vector<uint8_t> read_file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw BudgetError(path + ": cannot open");
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                             std::istreambuf_iterator<char>());
  if (in.bad()) throw BudgetError(path + ": read error");
  return bytes;
}

}  // namespace kestrel::budget
