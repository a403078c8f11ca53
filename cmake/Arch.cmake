# The instruction set the C++ code is compiled for (TESSERA_ARCH). The host's hot loops
# (the Embree packet lanes, the instant cache's gathers and scans) are written for GCC's
# vectoriser: with the x86-64 baseline (SSE2) it has 4-wide vectors, with x86-64-v3 (AVX2,
# 2013 on) 8-wide.
# Images are the same either way: FMA contraction stays off (CMakeLists.txt) and vector
# code rounds as scalar code does. Measured: bench/results/frame_times.md.
#   auto (default): x86-64-v3 when the compiler has it and the build machine runs it
#                   (AVX, AVX2, FMA, BMI1/2 tested: the names GCC and clang both know; the
#                   rest of v3 came with every such CPU), so the binary is for machines
#                   like it; else the compiler default;
#   none:           the compiler default;
#   anything else:  passed as -march=<value>.
set(TESSERA_ARCH auto CACHE STRING "C++ target: auto (x86-64-v3 if the build machine runs it), none, or a -march value")
set(TESSERA_MARCH "")
if(TESSERA_ARCH STREQUAL "auto")
  include(CheckCXXSourceRuns)
  set(CMAKE_REQUIRED_FLAGS -march=x86-64-v3)
  check_cxx_source_runs([=[
    int main() {
      __builtin_cpu_init();
      return __builtin_cpu_supports("avx") && __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") &&
             __builtin_cpu_supports("bmi") && __builtin_cpu_supports("bmi2") ? 0 : 1;
    }]=] TESSERA_HOST_RUNS_X86_64_V3)
  unset(CMAKE_REQUIRED_FLAGS)
  if(TESSERA_HOST_RUNS_X86_64_V3)
    set(TESSERA_MARCH x86-64-v3)
  endif()
elseif(NOT TESSERA_ARCH STREQUAL "none")
  set(TESSERA_MARCH ${TESSERA_ARCH})
endif()
if(TESSERA_MARCH)
  add_compile_options(-march=${TESSERA_MARCH})
endif()
message(STATUS "Tessera: C++ target -march=${TESSERA_MARCH} (TESSERA_ARCH=${TESSERA_ARCH}; empty: compiler default)")
