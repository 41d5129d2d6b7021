# The plugin ABI tag follows the public headers: a test fails when they change without a bump.
# usage: cmake -DROOT=<source dir> -P interface_digest.cmake
# The digest covers every public header with comments and white-space runs removed, so that
# documentation edits do not count; tests/plugin/interface.sha256 records "<ABI tag> <digest>".
file(GLOB headers ${ROOT}/include/emergent/*.hpp ${ROOT}/include/emergent/*.cuh)
list(SORT headers)
set(all "")
foreach(h IN LISTS headers)
  file(READ ${h} text)
  string(REGEX REPLACE "//[^\n]*" "" text "${text}")
  string(REGEX REPLACE "/\\*[^*]*\\*/" "" text "${text}")  # /*name*/ of unused parameters
  string(REGEX REPLACE "[ \t\r\n]+" " " text "${text}")
  get_filename_component(name ${h} NAME)
  string(APPEND all "${name}:${text}\n")
endforeach()
string(SHA256 digest "${all}")
file(READ ${ROOT}/include/emergent/plugin.hpp plugin)
string(REGEX MATCH "#define EMERGENT_PLUGIN_ABI \"([^\"]+)\"" _ "${plugin}")
set(tag ${CMAKE_MATCH_1})
file(STRINGS ${ROOT}/tests/plugin/interface.sha256 recorded LIMIT_COUNT 1)
separate_arguments(recorded)
list(GET recorded 0 recorded_tag)
list(GET recorded 1 recorded_digest)
if(NOT digest STREQUAL recorded_digest)
  if(tag STREQUAL recorded_tag)
    message(FATAL_ERROR "the public headers changed but EMERGENT_PLUGIN_ABI is still ${tag}: "
                        "bump it in include/emergent/plugin.hpp, then record "
                        "'<new tag> ${digest}' in tests/plugin/interface.sha256")
  endif()
  message(FATAL_ERROR "EMERGENT_PLUGIN_ABI is ${tag}: record '${tag} ${digest}' in "
                      "tests/plugin/interface.sha256")
endif()
if(NOT tag STREQUAL recorded_tag)
  message(FATAL_ERROR "EMERGENT_PLUGIN_ABI is ${tag} but the recorded interface is ${recorded_tag} "
                      "with the same headers: a bump without an interface change")
endif()
# Each tag says what changed, in docs/plugin_abi.md ("| 34 | ... |").
string(REGEX MATCH "[0-9]+$" number "${tag}")
file(READ ${ROOT}/docs/plugin_abi.md changes)
if(NOT changes MATCHES "\n\\| ${number} \\| [^|\n]*[A-Za-z]")
  message(FATAL_ERROR "docs/plugin_abi.md has no row for ${tag}: say what changed ('| ${number} | ... |')")
endif()
message(STATUS "plugin interface ${tag}: ${digest}")
