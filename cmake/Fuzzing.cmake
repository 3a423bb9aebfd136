# libFuzzer targets (tests/fuzz/), built on top of the ASan + UBSan build with clang.
option(CLOUDGRAPH_FUZZ "Build the libFuzzer targets in tests/fuzz (clang, with CLOUDGRAPH_SANITIZE)"
    OFF)
set(CLOUDGRAPH_FUZZ_SECONDS 20 CACHE STRING "seconds each fuzz target runs under ctest")

if(CLOUDGRAPH_FUZZ)
    if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
        message(FATAL_ERROR "CLOUDGRAPH_FUZZ=ON needs clang (libFuzzer); the C++ compiler is "
            "${CMAKE_CXX_COMPILER_ID}. Configure a fresh build directory with "
            "-DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++.")
    endif()
    if(NOT CLOUDGRAPH_SANITIZE)
        message(FATAL_ERROR "CLOUDGRAPH_FUZZ=ON needs -DCLOUDGRAPH_SANITIZE=ON: a fuzzer without "
            "AddressSanitizer and UndefinedBehaviorSanitizer misses most findings.")
    endif()
    if(NOT CLOUDGRAPH_BUILD_TESTS)
        message(FATAL_ERROR "CLOUDGRAPH_FUZZ=ON needs CLOUDGRAPH_BUILD_TESTS=ON (the targets live "
            "in tests/fuzz).")
    endif()
    include(CheckCXXSourceCompiles)
    set(CMAKE_REQUIRED_FLAGS -fsanitize=fuzzer)
    set(CMAKE_REQUIRED_LINK_OPTIONS -fsanitize=fuzzer)
    check_cxx_source_compiles([[
        #include <cstddef>
        #include <cstdint>
        extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t*, std::size_t) { return 0; }]]
        CLOUDGRAPH_HAVE_LIBFUZZER)
    unset(CMAKE_REQUIRED_FLAGS)
    unset(CMAKE_REQUIRED_LINK_OPTIONS)
    if(NOT CLOUDGRAPH_HAVE_LIBFUZZER)
        message(FATAL_ERROR "CLOUDGRAPH_FUZZ=ON: clang cannot link -fsanitize=fuzzer; install the "
            "libFuzzer runtime (Debian: libclang-rt-14-dev).")
    endif()
    # Coverage counters in every library, so the fuzzer is guided by the code under test and
    # not only by the harness. Only the fuzz targets link the libFuzzer runtime itself.
    add_compile_options(-fsanitize=fuzzer-no-link)
endif()

# cloudgraph_add_fuzzer(NAME): the target fuzz_NAME from NAME.cc in the calling directory, and
# a ctest (label fuzz) that runs it for CLOUDGRAPH_FUZZ_SECONDS on the seeds in corpus/NAME/.
function(cloudgraph_add_fuzzer name)
    set(target fuzz_${name})
    add_executable(${target} ${name}.cc)
    target_link_libraries(${target} PRIVATE cloudgraph_nodes cloudgraph_warnings)
    target_compile_options(${target} PRIVATE -fsanitize=fuzzer)
    target_link_options(${target} PRIVATE -fsanitize=fuzzer)
    add_test(NAME ${target}
        COMMAND "${CMAKE_CURRENT_SOURCE_DIR}/run_fuzzer.sh" "$<TARGET_FILE:${target}>"
            "${CMAKE_CURRENT_SOURCE_DIR}/corpus/${name}" "${CLOUDGRAPH_FUZZ_SECONDS}"
            "${CMAKE_BINARY_DIR}/fuzz-findings/${name}")
    # Generous: the machine may be busy with the rest of the suite.
    math(EXPR timeout "${CLOUDGRAPH_FUZZ_SECONDS} * 3 + 120")
    set_tests_properties(${target} PROPERTIES LABELS fuzz TIMEOUT ${timeout})
endfunction()
