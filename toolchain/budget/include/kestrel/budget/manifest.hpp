// The per-build-tree manifest that CMake writes (kestrel-budget-manifest.txt): what the build
// tree contains, so the host tool needs no knowledge of CMake's layout. Tab-separated lines:
//   target    overo
//   budget    /path/to/toolchain/budget-overo.txt
//   emulator  qemu-arm;-L;/          (';'-separated command, empty on the host)
//   bench     /path/to/kestrel-bench
//   bench_iters /path/to/kestrel-bench-iters
//   library   NAME  /path/libNAME.a  obj1.o;obj2.o
//   executable NAME /path/to/exe
#pragma once

#include <string>
#include <vector>

namespace kestrel::budget {

struct ManifestLibrary {
  std::string name;
  std::string archive;
  std::vector<std::string> objects;  // .su files sit beside them (foo.cpp.o -> foo.cpp.su)
};

struct Manifest {
  std::string path;
  std::string target;
  std::string budget_file;
  std::vector<std::string> emulator;
  std::string bench;
  std::string bench_iters;
  std::vector<ManifestLibrary> libraries;
  std::vector<std::pair<std::string, std::string>> executables;
};

Manifest load_manifest(const std::string& path);

// "dir/foo.cpp.o" -> "dir/foo.cpp.su" (GCC names the file after the object, minus ".o").
std::string stack_usage_path(const std::string& object);

}  // namespace kestrel::budget
