# Flags for the libFuzzer build (VOROHEX_FUZZ=ON), included by the top-level CMakeLists.txt
# before App/ so that every library is instrumented. Prerequisites (Debian): clang and
# libclang-rt-14-dev (libFuzzer and the sanitizer runtimes).
if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
  message(FATAL_ERROR
    "VOROHEX_FUZZ=ON needs clang (libFuzzer), but the C++ compiler is "
    "${CMAKE_CXX_COMPILER_ID} (${CMAKE_CXX_COMPILER}). Configure a fresh build directory with "
    "CC=clang CXX=clang++ cmake ... -DVOROHEX_FUZZ=ON "
    "(Debian packages: clang libclang-rt-14-dev).")
endif()

include(CheckCXXSourceCompiles)
set(CMAKE_REQUIRED_FLAGS "-fsanitize=fuzzer,address,undefined")
set(CMAKE_REQUIRED_LINK_OPTIONS "-fsanitize=fuzzer,address,undefined")
check_cxx_source_compiles([=[
#include <cstddef>
#include <cstdint>
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t*, std::size_t) { return 0; }
]=] VOROHEX_HAVE_LIBFUZZER)
unset(CMAKE_REQUIRED_FLAGS)
unset(CMAKE_REQUIRED_LINK_OPTIONS)
if(NOT VOROHEX_HAVE_LIBFUZZER)
  message(FATAL_ERROR
    "VOROHEX_FUZZ=ON: ${CMAKE_CXX_COMPILER} cannot link -fsanitize=fuzzer,address,undefined; "
    "install the sanitizer runtimes (Debian: apt-get install libclang-rt-14-dev).")
endif()

# Libraries: coverage instrumentation without libFuzzer's main, ASan and UBSan. UBSan
# findings abort (as ASan's do), so that libFuzzer records them as crashes.
add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined
                    -fno-omit-frame-pointer)
# Any executable linking them (e.g. the vorohex CLI, if built here) needs the runtimes.
add_link_options(-fsanitize=address,undefined)
