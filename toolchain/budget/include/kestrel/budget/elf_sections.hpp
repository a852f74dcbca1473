// Section-size summary of one ELF file (relocatable object or linked executable).
//
// The budget tool reads section headers only, which is enough to split a file's memory into
// code, read-only data and static RAM. 32- and 64-bit little-endian ELF are accepted (the ARM
// targets are ELF32; 64-bit lets host-built fixtures exercise the same code).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "kestrel/budget/error.hpp"

namespace kestrel::budget {

struct SectionSizes {
  uint64_t code = 0;    // SHF_ALLOC + SHF_EXECINSTR (.text and friends)
  uint64_t rodata = 0;  // SHF_ALLOC, neither writable nor executable (.rodata, .ARM.exidx)
  uint64_t data = 0;    // SHF_ALLOC + SHF_WRITE with file contents (.data, .init_array)
  uint64_t bss = 0;     // SHF_ALLOC + SHT_NOBITS (.bss, .tbss)
  uint64_t ram() const { return data + bss; }
  SectionSizes& operator+=(const SectionSizes& o) {
    code += o.code;
    rodata += o.rodata;
    data += o.data;
    bss += o.bss;
    return *this;
  }
};

struct ElfInfo {
  bool is_64 = false;
  uint16_t machine = 0;  // e_machine: 40 = ARM, 62 = x86-64
  SectionSizes sizes;
};

// Parses the section headers of an ELF image held in memory. `what` names it in errors.
ElfInfo parse_elf(std::span<const uint8_t> image, const std::string& what);

// Reads a whole file; throws BudgetError when it cannot.
std::vector<uint8_t> read_file_bytes(const std::string& path);

}  // namespace kestrel::budget
