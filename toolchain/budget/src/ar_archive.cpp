#include "kestrel/budget/ar_archive.hpp"

#include <cstring>

#include "kestrel/budget/error.hpp"

namespace kestrel::budget {
namespace {

constexpr char kMagic[] = "!<arch>\n";
constexpr size_t kMagicLen = 8;
constexpr size_t kHeaderLen = 60;  // name16 date12 uid6 gid6 mode8 size10 fmag2

std::string field(std::span<const uint8_t> b, size_t off, size_t len) {
  std::string s(reinterpret_cast<const char*>(b.data() + off), len);
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

uint64_t decimal(const std::string& s, const std::string& what) {
  if (s.empty()) throw BudgetError(what + ": malformed archive member header");
  uint64_t v = 0;
  for (char c : s) {
    if (c < '0' || c > '9' || v > (UINT64_MAX - 9) / 10) {
      throw BudgetError(what + ": malformed archive member header");
    }
    v = v * 10 + static_cast<uint64_t>(c - '0');
  }
  return v;
}

}  // namespace

bool looks_like_ar(std::span<const uint8_t> image) {
  return image.size() >= kMagicLen && std::memcmp(image.data(), kMagic, kMagicLen) == 0;
}

std::vector<ArMember> parse_ar(std::span<const uint8_t> image, const std::string& what) {
  if (!looks_like_ar(image)) throw BudgetError(what + ": not an ar archive");
  std::vector<ArMember> members;
  std::span<const uint8_t> long_names;
  size_t pos = kMagicLen;
  while (pos < image.size()) {
    if (image.size() - pos < kHeaderLen) throw BudgetError(what + ": truncated archive header");
    if (image[pos + 58] != '`' || image[pos + 59] != '\n') {
      throw BudgetError(what + ": bad archive member magic at offset " + std::to_string(pos));
    }
    std::string name = field(image, pos, 16);
    const uint64_t size = decimal(field(image, pos + 48, 10), what);
    const size_t data = pos + kHeaderLen;
    if (size > image.size() - data) throw BudgetError(what + ": truncated archive member");
    const std::span<const uint8_t> bytes = image.subspan(data, size);
    pos = data + size + (size & 1);  // members are 2-byte aligned

    if (name == "/" || name == "/SYM64/" || name == "__.SYMDEF" || name == "__.SYMDEF SORTED") {
      continue;  // symbol index
    }
    if (name == "//") {
      long_names = bytes;
      continue;
    }
    if (name.size() > 1 && name[0] == '/') {  // GNU long name: "/offset" into "//"
      const uint64_t off = decimal(name.substr(1), what);
      if (off >= long_names.size()) throw BudgetError(what + ": bad long member name offset");
      size_t end = off;
      while (end < long_names.size() && long_names[end] != '/' && long_names[end] != '\n') ++end;
      name.assign(reinterpret_cast<const char*>(long_names.data() + off), end - off);
    } else if (!name.empty() && name.back() == '/') {
      name.pop_back();
    }
    members.push_back({name, bytes});
  }
  return members;
}

}  // namespace kestrel::budget
