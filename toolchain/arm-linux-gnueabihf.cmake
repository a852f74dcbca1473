# Overo-class board: TI OMAP3530, ARM Cortex-A8 at 720 MHz, NEON, hard float.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR armv7-a)
set(KESTREL_TRIPLE arm-linux-gnueabihf)
set(KESTREL_TARGET overo CACHE STRING "" FORCE)
set(KESTREL_ARCH_FLAGS "-mcpu=cortex-a8 -mfpu=neon -mfloat-abi=hard")
include(${CMAKE_CURRENT_LIST_DIR}/cmake/ArmCommon.cmake)
