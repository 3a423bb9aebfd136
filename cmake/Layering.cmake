# The architecture, enforced by the compiler: a library sees only the folders of the libraries
# it links. cloudgraph_folder(<target> <folder>) publishes <folder> through an include root of
# its own (build/include/<folder>/<folder> -> the source folder), and no target adds the
# project root, so `#include "core/Node.h"` in algo/ fails to compile: "file not found".
#
#   util     <- nothing of ours
#   algo     <- util
#   formats  <- util
#   core     <- util
#   nodes    <- core, algo, formats, util
#   cli      <- nodes, core, algo, formats, util
function(cloudgraph_folder target folder)
    set(root "${CMAKE_BINARY_DIR}/include/${folder}")
    file(MAKE_DIRECTORY "${root}")
    file(CREATE_LINK "${PROJECT_SOURCE_DIR}/${folder}" "${root}/${folder}" SYMBOLIC)
    target_include_directories(${target} PUBLIC "${root}")
endfunction()
