# Warning flags for every CloudGraph target, and the optional sanitizer build.
add_library(cloudgraph_warnings INTERFACE)
target_compile_options(cloudgraph_warnings INTERFACE -Wall -Wextra -Wpedantic -Wshadow
    -Wnon-virtual-dtor -Wold-style-cast -Wcast-align -Woverloaded-virtual)
if(CLOUDGRAPH_WERROR)
    target_compile_options(cloudgraph_warnings INTERFACE -Werror)
endif()

if(CLOUDGRAPH_SANITIZE)
    set(_san -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer)
    add_compile_options(${_san})
    add_link_options(${_san})
    if(CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
        add_compile_options(
            "-fsanitize-ignorelist=${CMAKE_CURRENT_LIST_DIR}/sanitizer-ignorelist.txt")
    endif()
endif()
