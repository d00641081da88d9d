# Helpers that give every flexmbs target the same language level and warnings.

# flexmbs_warnings(<target>): the project's warning set, an error in CI builds.
function(flexmbs_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow
                                           -Wnon-virtual-dtor -Wold-style-cast)
  if(FLEXMBS_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# flexmbs_library(<name> SOURCES ... [PUBLIC_DEPS ...] [PRIVATE_DEPS ...]):
# a module library `flexmbs_<name>` with alias `flexmbs::<name>`; headers are
# included as "<module>/<file>.h" from the source root.
function(flexmbs_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(flexmbs_${name} ${ARG_SOURCES})
  add_library(flexmbs::${name} ALIAS flexmbs_${name})
  target_include_directories(flexmbs_${name} PUBLIC ${PROJECT_SOURCE_DIR})
  target_link_libraries(flexmbs_${name} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  flexmbs_warnings(flexmbs_${name})
endfunction()
