# Cross toolchain for the firmware build (Cortex-M4F, Debian's gcc-arm-none-eabi and
# libnewlib-arm-none-eabi). Use with -DHV_FIRMWARE=ON:
#   cmake -S . -B build-fw -G Ninja -DCMAKE_TOOLCHAIN_FILE=cmake/arm-none-eabi.cmake -DHV_FIRMWARE=ON
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)

set(CMAKE_C_COMPILER arm-none-eabi-gcc)
set(CMAKE_CXX_COMPILER arm-none-eabi-g++)
set(CMAKE_ASM_COMPILER arm-none-eabi-gcc)
set(CMAKE_AR arm-none-eabi-ar)
set(CMAKE_RANLIB arm-none-eabi-ranlib)
set(HV_FW_SIZE arm-none-eabi-size CACHE STRING "size tool of the cross toolchain")
set(HV_FW_NM arm-none-eabi-nm CACHE STRING "nm of the cross toolchain")

# Cortex-M4 with the single-precision FPU, hard-float calling convention.
set(HV_FW_CPU_FLAGS "-mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16")
# Sections per function and object so the linker drops what the image never calls.
set(CMAKE_C_FLAGS_INIT "${HV_FW_CPU_FLAGS} -ffunction-sections -fdata-sections")
set(CMAKE_CXX_FLAGS_INIT "${HV_FW_CPU_FLAGS} -ffunction-sections -fdata-sections")
set(CMAKE_ASM_FLAGS_INIT "${HV_FW_CPU_FLAGS}")
# newlib-nano for string functions and libm; no host start files (firmware/ brings its own).
set(CMAKE_EXE_LINKER_FLAGS_INIT "${HV_FW_CPU_FLAGS} --specs=nano.specs -nostartfiles -Wl,--gc-sections")

# No executables can run on the build machine: test the compiler with a library.
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
