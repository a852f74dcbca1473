#include "kestrel/budget/manifest.hpp"

#include <fstream>

#include "kestrel/budget/error.hpp"

namespace kestrel::budget {
namespace {

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  size_t start = 0;
  while (true) {
    const size_t p = s.find(sep, start);
    out.push_back(s.substr(start, p - start));
    if (p == std::string::npos) break;
    start = p + 1;
  }
  return out;
}

}  // namespace

std::string stack_usage_path(const std::string& object) {
  const size_t dot = object.rfind('.');
  const size_t slash = object.rfind('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
    return object + ".su";
  return object.substr(0, dot) + ".su";
}

Manifest load_manifest(const std::string& path) {
  std::ifstream in(path);
  if (!in) {
    throw BudgetError(path + ": cannot open manifest (configure the build tree with CMake first)");
  }
  Manifest m;
  m.path = path;
  std::string line;
  size_t line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty()) continue;
    const std::vector<std::string> f = split(line, '\t');
    const std::string where = path + ":" + std::to_string(line_no);
    const auto need = [&](size_t n) {
      if (f.size() != n) throw BudgetError(where + ": expected " + std::to_string(n) + " fields");
    };
    if (f[0] == "target") {
      need(2);
      m.target = f[1];
    } else if (f[0] == "budget") {
      need(2);
      m.budget_file = f[1];
    } else if (f[0] == "emulator") {
      need(2);
      if (!f[1].empty()) m.emulator = split(f[1], ';');
    } else if (f[0] == "bench") {
      need(2);
      m.bench = f[1];
    } else if (f[0] == "bench_iters") {
      need(2);
      m.bench_iters = f[1];
    } else if (f[0] == "library") {
      need(4);
      ManifestLibrary lib{f[1], f[2], {}};
      if (!f[3].empty()) lib.objects = split(f[3], ';');
      m.libraries.push_back(std::move(lib));
    } else if (f[0] == "executable") {
      need(3);
      m.executables.emplace_back(f[1], f[2]);
    } else {
      throw BudgetError(where + ": unknown manifest entry '" + f[0] + "'");
    }
  }
  if (m.target.empty()) throw BudgetError(path + ": manifest without a target line");
  return m;
}

}  // namespace kestrel::budget
