# Verdex-class board: Marvell PXA270 (XScale, ARMv5TE) at 400 MHz, no FPU: soft float.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR armv5te)
set(KESTREL_TRIPLE arm-linux-gnueabi)
set(KESTREL_TARGET verdex CACHE STRING "" FORCE)
set(KESTREL_ARCH_FLAGS "-march=armv5te -mtune=xscale -mfloat-abi=soft")
include(${CMAKE_CURRENT_LIST_DIR}/cmake/ArmCommon.cmake)
