# Compiler policy as INTERFACE targets, linked by every aasim target (style.md habit 2).

add_library(aasim_warnings INTERFACE)
target_compile_options(aasim_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wcast-align -Wunused
  -Woverloaded-virtual -Wnull-dereference -Wdouble-promotion -Wimplicit-fallthrough)
if(AASIM_WERROR)
  target_compile_options(aasim_warnings INTERFACE -Werror)
endif()

add_library(aasim_opt INTERFACE)
# The passes reproduce reference shaders' float32 arithmetic, where a*b + c is two roundings
# (aa-facts §1.9), and the 8-bit conversions of sim/formats.h round through a float add: no
# contraction into fused multiply-adds, in any target, by any compiler (clang contracts by
# default, even when it folds constants on a target without FMA instructions).
target_compile_options(aasim_opt INTERFACE -ffp-contract=off)
set(AASIM_MARCH "x86-64-v2" CACHE STRING "-march for every aasim target (empty: the compiler's default)")
if(AASIM_MARCH AND CMAKE_SYSTEM_PROCESSOR MATCHES "x86_64|AMD64")
  target_compile_options(aasim_opt INTERFACE -march=${AASIM_MARCH})
endif()
if(AASIM_SANITIZE)
  # -g1: line tables are all a sanitizer report's stack trace needs; full debug info only makes
  # the CI's sanitized build slower to compile and link.
  target_compile_options(aasim_opt INTERFACE -fsanitize=address,undefined -fno-sanitize-recover=all
                                             -fno-omit-frame-pointer -O1 -g1)
  target_link_options(aasim_opt INTERFACE -fsanitize=address,undefined)
  # Release flags (NDEBUG) still get the AASIM_DCHECK tier of sim/check.h.
  target_compile_definitions(aasim_opt INTERFACE AASIM_DCHECKS)
endif()

if(AASIM_TSAN)
  if(AASIM_SANITIZE OR AASIM_FUZZ)
    message(FATAL_ERROR "AASIM_TSAN cannot be combined with AddressSanitizer (AASIM_SANITIZE, AASIM_FUZZ)")
  endif()
  # GCC 12's flow analysis sees TSan's instrumentation as a possible null dereference inside
  # nlohmann::json (is_array() in scenes/gltf_loader.cpp); every other build keeps the warning.
  # -O1: the TSan build compiles every library CI's step needs, and -O2 costs more compile time
  # than it saves in its 15 s of tests.
  target_compile_options(aasim_opt INTERFACE -fsanitize=thread -fno-omit-frame-pointer -O1 -g1
                                             -Wno-null-dereference)
  target_link_options(aasim_opt INTERFACE -fsanitize=thread)
  # tbb::parallel_for on std::threads TSan can follow (tests/tsan/oneapi/tbb/parallel_for.h):
  # ahead of the system headers on every target's include path.
  target_include_directories(aasim_opt BEFORE INTERFACE ${PROJECT_SOURCE_DIR}/tests/tsan)
endif()

if(AASIM_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "AASIM_FUZZ needs clang (libFuzzer): configure with CXX=clang++")
  endif()
  # Libraries get coverage instrumentation without libFuzzer's main; fuzz/ links the main.
  target_compile_options(aasim_opt INTERFACE -fsanitize=fuzzer-no-link,address,undefined
                                             -fno-sanitize-recover=all -fno-omit-frame-pointer -O1 -g1)
  target_link_options(aasim_opt INTERFACE -fsanitize=address,undefined)
  target_compile_definitions(aasim_opt INTERFACE AASIM_DCHECKS)
endif()

# A target whose own code is not what anything times (the CLI test files: they drive the aasim
# binary and read its files) sets the property AASIM_UNOPTIMISED and compiles at -O0, after
# whichever level the build type or a sanitizer chose above.
target_compile_options(aasim_opt INTERFACE $<$<BOOL:$<TARGET_PROPERTY:AASIM_UNOPTIMISED>>:-O0>)
# A target whose third-party headers trip GCC's -Wnull-dereference with a false positive (see
# cli/CMakeLists.txt) sets AASIM_NO_GCC_NULL_DEREFERENCE: after aasim_warnings, so it wins.
target_compile_options(aasim_opt INTERFACE
  $<$<AND:$<BOOL:$<TARGET_PROPERTY:AASIM_NO_GCC_NULL_DEREFERENCE>>,$<CXX_COMPILER_ID:GNU>>:-Wno-null-dereference>)

# Every aasim library and executable links this one target.
add_library(aasim_policy INTERFACE)
target_link_libraries(aasim_policy INTERFACE aasim_warnings aasim_opt)
