# Shared part of the two ARM toolchain files: Debian's cross compilers, the multiarch
# libraries of the target architecture, and qemu-arm to run tests and benchmarks.
set(CMAKE_C_COMPILER ${KESTREL_TRIPLE}-gcc)
set(CMAKE_CXX_COMPILER ${KESTREL_TRIPLE}-g++)
set(CMAKE_C_FLAGS_INIT "${KESTREL_ARCH_FLAGS}")
set(CMAKE_CXX_FLAGS_INIT "${KESTREL_ARCH_FLAGS}")

# Headers are shared between architectures (Eigen, libccd's and GoogleTest's are
# Multi-Arch: same); libraries and CMake package files come from the multiarch folders.
set(CMAKE_LIBRARY_ARCHITECTURE ${KESTREL_TRIPLE})
set(CMAKE_FIND_ROOT_PATH /usr/${KESTREL_TRIPLE} /usr/lib/${KESTREL_TRIPLE} /usr)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE BOTH)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
set(CMAKE_PREFIX_PATH /usr/lib/${KESTREL_TRIPLE}/cmake /usr/share/eigen3/cmake)

# Tests run under qemu-arm against the multiarch runtime (libc6, libstdc++6 of the target
# architecture, installed beside the host's): `-L /` makes qemu resolve the target's loader,
# /lib/ld-linux*.so.3, from the host root, and that loader finds its libraries in
# /lib/TRIPLE and /usr/lib/TRIPLE. The cross compiler's own sysroot in /usr/TRIPLE carries an
# older glibc build than the multiarch libraries and must not be mixed with them.
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-arm -L /)
