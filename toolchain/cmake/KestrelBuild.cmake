# Build rules shared by every kestrel target.
#
# Firmware code (core, hal, modules, platform) is built with warnings as errors, without
# exceptions or RTTI, with per-function stack usage files for the budget checker, and with
# -fno-associative-math so that host and targets compute the same floating-point results.
# Host tools and tests keep the defaults, but still warn.

set(KESTREL_TARGET "host" CACHE STRING "host, overo or verdex")
set_property(CACHE KESTREL_TARGET PROPERTY STRINGS host overo verdex)
if(NOT KESTREL_TARGET MATCHES "^(host|overo|verdex)$")
  message(FATAL_ERROR "KESTREL_TARGET must be host, overo or verdex, not '${KESTREL_TARGET}'")
endif()

# RTTI is off everywhere, not only in firmware: a test or tool that touches a polymorphic
# firmware class (a HAL driver) needs its typeinfo, which -fno-rtti code never emits.
add_compile_options($<$<COMPILE_LANGUAGE:CXX>:-fno-rtti>)

# The tests' own files may compile with other optimisation than the build type's (an -O flag;
# empty: the build type's), tests/CMakeLists.txt says why.
set(KESTREL_TEST_OPTIMIZATION "" CACHE STRING "optimisation flag of the tests' own files")

set(KESTREL_COMMON_WARNINGS -Wall -Wextra -Werror -Werror=shadow -Werror=undef
    -Wno-psabi -Wno-missing-field-initializers)
# -Wno-psabi: GCC's notes on an old ARM ABI change are not about our code.
# -Wno-missing-field-initializers: aggregates rely on default member initialisers.
set(KESTREL_FIRMWARE_FLAGS ${KESTREL_COMMON_WARNINGS} -fno-exceptions
    -fno-associative-math -fstack-usage)
if(CMAKE_CROSSCOMPILING)
  list(APPEND KESTREL_FIRMWARE_FLAGS -Wframe-larger-than=16384)
endif()

# Firmware library: one per folder of core/hal/modules/platform, with its own include dir.
function(kestrel_firmware_library name)
  cmake_parse_arguments(ARG "INTERFACE" "" "SOURCES;DEPS" ${ARGN})
  if(ARG_INTERFACE)
    add_library(${name} INTERFACE)
    target_include_directories(${name} INTERFACE ${CMAKE_CURRENT_SOURCE_DIR}/include)
    target_link_libraries(${name} INTERFACE ${ARG_DEPS})
  else()
    add_library(${name} STATIC ${ARG_SOURCES})
    target_include_directories(${name} PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include)
    target_link_libraries(${name} PUBLIC ${ARG_DEPS})
    target_compile_options(${name} PRIVATE ${KESTREL_FIRMWARE_FLAGS})
    set_property(GLOBAL APPEND PROPERTY KESTREL_FIRMWARE_LIBS ${name})
  endif()
  add_library(kestrel::${name} ALIAS ${name})
endfunction()

# Host tool or simulator library: may use the standard library freely (it runs before arming
# or off the vehicle), but still builds warning-free.
function(kestrel_host_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(${name} STATIC ${ARG_SOURCES})
  target_include_directories(${name} PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include)
  target_link_libraries(${name} PUBLIC ${ARG_DEPS})
  target_compile_options(${name} PRIVATE ${KESTREL_COMMON_WARNINGS})
  add_library(kestrel::${name} ALIAS ${name})
endfunction()

function(kestrel_executable name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS})
  target_compile_options(${name} PRIVATE ${KESTREL_COMMON_WARNINGS})
endfunction()

# A GoogleTest executable registered with CTest; under the ARM presets CTest runs it through
# CMAKE_CROSSCOMPILING_EMULATOR (qemu-arm). LABELS lets CI pick groups (unit, sim, realdata).
# PARTS (GoogleTest filters, Suite.Test) registers one CTest test per filter, `name.Test`, plus
# `name.rest` for every test no filter names, so a binary of long flights runs on all of CI's
# cores and a preset can leave one flight out by its name.
function(kestrel_test name)
  cmake_parse_arguments(ARG "" "TIMEOUT" "SOURCES;DEPS;LABELS;PARTS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} kestrel_test_support GTest::gtest)
  target_compile_options(${name} PRIVATE ${KESTREL_TEST_FLAGS})
  target_precompile_headers(${name} REUSE_FROM kestrel_test_pch)
  target_compile_definitions(${name} PRIVATE
      KESTREL_SOURCE_DIR="${CMAKE_SOURCE_DIR}"
      KESTREL_SHARED_DATA_DIR="${CMAKE_SOURCE_DIR}/../shared/data")
  if(NOT ARG_TIMEOUT)
    set(ARG_TIMEOUT 600)
  endif()
  if(NOT ARG_LABELS)
    set(ARG_LABELS unit)
  endif()
  if(NOT ARG_PARTS)
    add_test(NAME ${name} COMMAND ${name} --gtest_brief=1)
    set_tests_properties(${name} PROPERTIES TIMEOUT ${ARG_TIMEOUT} LABELS "${ARG_LABELS}")
    return()
  endif()
  # A fresh clone has no CTest cost data, so the parts would start in declaration order; a
  # high COST starts them first, before the short tests that can fill in beside them.
  foreach(filter ${ARG_PARTS})
    string(REGEX REPLACE "^.*\\." "" part ${filter})
    add_test(NAME ${name}.${part} COMMAND ${name} --gtest_brief=1 --gtest_filter=${filter})
    set_tests_properties(${name}.${part} PROPERTIES
        TIMEOUT ${ARG_TIMEOUT} LABELS "${ARG_LABELS}" COST 1000)
  endforeach()
  list(JOIN ARG_PARTS ":" named)
  add_test(NAME ${name}.rest COMMAND ${name} --gtest_brief=1 --gtest_filter=-${named})
  set_tests_properties(${name}.rest PROPERTIES TIMEOUT ${ARG_TIMEOUT} LABELS "${ARG_LABELS}")
endfunction()

# Benchmarks: each module lists its benchmark sources here; tests/bench links them all into
# one kestrel-bench so names stay `module/case` and one binary serves every preset.
function(kestrel_benchmarks)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  foreach(src ${ARG_SOURCES})
    get_filename_component(abs ${src} ABSOLUTE)
    set_property(GLOBAL APPEND PROPERTY KESTREL_BENCH_SOURCES ${abs})
  endforeach()
  set_property(GLOBAL APPEND PROPERTY KESTREL_BENCH_DEPS ${ARG_DEPS})
endfunction()

# Adds every immediate sub-folder holding a CMakeLists.txt, so new modules and test groups
# join the build by existing.
function(kestrel_add_subfolders)
  file(GLOB children LIST_DIRECTORIES true RELATIVE ${CMAKE_CURRENT_SOURCE_DIR}
       ${CMAKE_CURRENT_SOURCE_DIR}/*)
  list(SORT children)
  foreach(child ${children})
    if(IS_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/${child}
       AND EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/${child}/CMakeLists.txt)
      add_subdirectory(${child})
    endif()
  endforeach()
endfunction()
