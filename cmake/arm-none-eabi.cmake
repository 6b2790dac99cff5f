# CMake toolchain file: arm-none-eabi GCC for an Arm Cortex-M3 without FPU, bare metal.
#
# Libraries: the full newlib (libc.a, libstdc++.a) with semihosting (librdimon.a), through
# --specs=rdimon.specs. Not newlib-nano: its printf has no 64-bit integers (%llu, PRIu64),
# which the instruction counts need. C++ without exceptions and RTTI.
#
# The board (vector table, reset, linker script) comes from testbench/cortex_m3, which links
# with -nostartfiles: rdimon's own crt0 is not used.
#
#   cmake -S testbench/cortex_m3 -B build-fw -DCMAKE_TOOLCHAIN_FILE=$PWD/cmake/arm-none-eabi.cmake
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)

set(CMAKE_C_COMPILER arm-none-eabi-gcc)
set(CMAKE_CXX_COMPILER arm-none-eabi-g++)
set(CMAKE_ASM_COMPILER arm-none-eabi-gcc)
find_program(CMAKE_SIZE arm-none-eabi-size)

# The compiler checks cannot link an executable without the board's startup and linker script.
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

set(_intgrid_cpu_flags "-mcpu=cortex-m3 -mthumb -mfloat-abi=soft")
# One section per function and object, so that --gc-sections drops what is unused.
set(_intgrid_section_flags "-ffunction-sections -fdata-sections")

set(CMAKE_C_FLAGS_INIT "${_intgrid_cpu_flags} ${_intgrid_section_flags}")
set(CMAKE_CXX_FLAGS_INIT "${_intgrid_cpu_flags} ${_intgrid_section_flags} -fno-exceptions -fno-rtti")
set(CMAKE_ASM_FLAGS_INIT "${_intgrid_cpu_flags}")
set(CMAKE_EXE_LINKER_FLAGS_INIT "${_intgrid_cpu_flags} --specs=rdimon.specs -Wl,--gc-sections")

# CMake defines $<LINK_LIBRARY:WHOLE_ARCHIVE,...> per platform, not for Generic: GNU ld's.
set(CMAKE_LINK_LIBRARY_USING_WHOLE_ARCHIVE
    "LINKER:--whole-archive" "<LINK_ITEM>" "LINKER:--no-whole-archive")
set(CMAKE_LINK_LIBRARY_USING_WHOLE_ARCHIVE_SUPPORTED TRUE)

# Release is -O2 (CMake's is -O3): smaller code, closer to what firmware ships with. Cache
# entries, since CMake appends its own -O3 to a *_FLAGS_RELEASE_INIT.
set(CMAKE_C_FLAGS_RELEASE "-O2 -DNDEBUG" CACHE STRING "Flags of Release builds")
set(CMAKE_CXX_FLAGS_RELEASE "-O2 -DNDEBUG" CACHE STRING "Flags of Release builds")
