# Writes OUT from IN with the project version and the git commit of SRC, at every build
# (a custom target runs it), so a rebuilt binary never reports the commit of an older
# configure. configure_file leaves OUT untouched when nothing changed: no needless rebuild.
execute_process(COMMAND git rev-parse --short=12 HEAD WORKING_DIRECTORY ${SRC}
                OUTPUT_VARIABLE FLOTSAM_GIT_COMMIT OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
if(NOT FLOTSAM_GIT_COMMIT)
  set(FLOTSAM_GIT_COMMIT "unknown commit")
else()
  execute_process(COMMAND git status --porcelain --untracked-files=no WORKING_DIRECTORY ${SRC}
                  OUTPUT_VARIABLE FLOTSAM_GIT_CHANGES OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if(FLOTSAM_GIT_CHANGES)
    string(APPEND FLOTSAM_GIT_COMMIT "-dirty")
  endif()
endif()
configure_file(${IN} ${OUT} @ONLY)
