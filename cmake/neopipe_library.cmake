# The libraries neopipe installs, and how each is declared so that the same target works in this
# build tree and from an installed package.

# neopipe_public_library(TARGET NAME HEADERS...): TARGET is an installed library, known to users as
# neopipe::NAME (an ALIAS of the same name here, so a project that adds neopipe's source tree links
# exactly what a find_package user links). HEADERS are its public headers, relative to the source
# root ("pipeline/graph_spec.hpp"): the ones a user needs; every other header stays internal.
function(neopipe_public_library target name)
  add_library(neopipe::${name} ALIAS ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${name}
    # The Python module links these static libraries into a shared object, which needs PIC. Set here
    # rather than through CMAKE_POSITION_INDEPENDENT_CODE so the executables and tests keep their
    # compile lines (and their ccache entries).
    POSITION_INDEPENDENT_CODE ON)
  # Installed headers keep their "module/header.hpp" paths under include/neopipe/, so a user writes
  # the same #include lines as neopipe's own code without a generic "pipeline/" in include/.
  target_include_directories(${target} PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}>
    $<BUILD_INTERFACE:${PROJECT_BINARY_DIR}/generated> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/neopipe>)
  # The headers use C++20 (designated initialisers, <span>, defaulted comparisons): users need it too.
  target_compile_features(${target} PUBLIC cxx_std_20)
  set_property(GLOBAL APPEND PROPERTY NEOPIPE_PUBLIC_TARGETS ${target})
  foreach(header IN LISTS ARGN)
    set_property(GLOBAL APPEND PROPERTY NEOPIPE_PUBLIC_HEADERS ${header})
  endforeach()
endfunction()
