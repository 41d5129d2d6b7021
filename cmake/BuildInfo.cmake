# Writes the build-info header at every build (not only at configure): the source revision a
# binary records in its output files must be the one it was compiled from. The header is
# rewritten only when the revision changed, so an unchanged tree rebuilds nothing.
# usage: cmake -DSOURCE_DIR=... -DTEMPLATE=... -DOUTPUT=... -DPROJECT_VERSION=... -P BuildInfo.cmake
execute_process(COMMAND git rev-parse --short=12 HEAD WORKING_DIRECTORY ${SOURCE_DIR}
                OUTPUT_VARIABLE EMERGENT_GIT_COMMIT OUTPUT_STRIP_TRAILING_WHITESPACE
                ERROR_QUIET RESULT_VARIABLE git_result)
if(NOT git_result EQUAL 0 OR NOT EMERGENT_GIT_COMMIT)
  set(EMERGENT_GIT_COMMIT unknown)
else()
  # Source changes not yet committed: say so, since the commit alone does not name the code.
  execute_process(COMMAND git diff --quiet HEAD -- src include decomposition problems CMakeLists.txt
                  WORKING_DIRECTORY ${SOURCE_DIR} RESULT_VARIABLE dirty ERROR_QUIET)
  if(NOT dirty EQUAL 0)
    string(APPEND EMERGENT_GIT_COMMIT "-modified")
  endif()
endif()
configure_file(${TEMPLATE} ${OUTPUT} @ONLY)
