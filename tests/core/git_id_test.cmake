# lib/git_id.cmake against a scratch git repository with known states: a clean tree gives the
# commit, an edit or an untracked file in the built sources a dirty id that names that edit (the
# same edit the same id, another edit another), an edit elsewhere (data, docs) no dirty id, a
# commit the new commit; the header is not rewritten while the id stands; no git gives "unknown".
# Usage: cmake -DSCRIPT=<lib/git_id.cmake> -DWORK=<scratch folder> -P git_id_test.cmake
cmake_minimum_required(VERSION 3.21)

file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK}/repo/lib ${WORK}/repo/sweeps ${WORK}/repo/data ${WORK}/plain)
set(header ${WORK}/id.hpp)
# git must not find a repository above WORK (the build tree usually sits in the project's).
set(ENV{GIT_CEILING_DIRECTORIES} ${WORK})

function(git)
  execute_process(COMMAND git -c user.name=test -c user.email=test@example.invalid ${ARGN}
    WORKING_DIRECTORY ${WORK}/repo RESULT_VARIABLE failed OUTPUT_QUIET ERROR_VARIABLE err)
  if(failed)
    message(FATAL_ERROR "git ${ARGN}: ${err}")
  endif()
endfunction()

# Commits everything in the scratch repository; `var` gets the commit's 12-hex id.
function(commit_all message var)
  git(add -A)
  git(commit -q -m ${message})
  execute_process(COMMAND git rev-parse --short=12 HEAD WORKING_DIRECTORY ${WORK}/repo
    OUTPUT_VARIABLE commit OUTPUT_STRIP_TRAILING_WHITESPACE)
  set(${var} "${commit}" PARENT_SCOPE)
endfunction()

# The id the script writes for SOURCE_DIR = dir, into `var`.
function(id_of dir var)
  execute_process(COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${dir} -DOUT=${header} -P ${SCRIPT}
    RESULT_VARIABLE failed ERROR_VARIABLE err)
  if(failed)
    message(FATAL_ERROR "git_id.cmake failed: ${err}")
  endif()
  file(STRINGS ${header} line REGEX "^#define SLIPWALK_GIT_COMMIT \"")
  string(REGEX REPLACE "^#define SLIPWALK_GIT_COMMIT \"(.*)\"$" "\\1" id "${line}")
  set(${var} "${id}" PARENT_SCOPE)
endfunction()

function(expect what actual expected)
  if(NOT actual STREQUAL expected)
    message(FATAL_ERROR "${what}: got \"${actual}\", expected \"${expected}\"")
  endif()
endfunction()

function(expect_differ what one other)
  if(one STREQUAL other)
    message(FATAL_ERROR "${what}: both \"${one}\"")
  endif()
endfunction()

function(expect_match what actual regex)
  if(NOT actual MATCHES "${regex}")
    message(FATAL_ERROR "${what}: got \"${actual}\", expected a match of ${regex}")
  endif()
endfunction()

# ---- a clean tree: the commit itself ------------------------------------------------------------
git(init -q)
file(WRITE ${WORK}/repo/lib/a.cpp "int a() { return 1; }\n")
file(WRITE ${WORK}/repo/data/notes.txt "notes\n")
commit_all(first first)
id_of(${WORK}/repo clean)
expect("a clean tree" "${clean}" "${first}")

# ---- the header stands while the id does (nothing recompiles) ----------------------------------
file(TIMESTAMP ${header} before "%s")
execute_process(COMMAND ${CMAKE_COMMAND} -E sleep 1.1)
id_of(${WORK}/repo again)
file(TIMESTAMP ${header} after "%s")
expect("the header's time with an unchanged id" "${after}" "${before}")

# ---- edits in the built sources: dirty, and the id names the edit ------------------------------
file(WRITE ${WORK}/repo/lib/a.cpp "int a() { return 2; }\n")
id_of(${WORK}/repo edit_two)
expect_match("an edited source" "${edit_two}" "^${first}-dirty-[0-9a-f]+$")
string(LENGTH "${edit_two}" length)
expect("the length of <12-hex commit>-dirty-<12-hex hash>" "${length}" "31")
id_of(${WORK}/repo edit_two_again)
expect("the same edit" "${edit_two_again}" "${edit_two}")
file(WRITE ${WORK}/repo/lib/a.cpp "int a() { return 3; }\n")
id_of(${WORK}/repo edit_three)
expect_differ("two different edits" "${edit_three}" "${edit_two}")
file(WRITE ${WORK}/repo/lib/a.cpp "int a() { return 1; }\n")
id_of(${WORK}/repo reverted)
expect("an edit undone" "${reverted}" "${first}")

# ---- an untracked file the build globs picks up --------------------------------------------------
file(WRITE ${WORK}/repo/sweeps/new.cpp "int b() { return 1; }\n")
id_of(${WORK}/repo untracked)
expect_match("an untracked source" "${untracked}" "^${first}-dirty-")
file(WRITE ${WORK}/repo/sweeps/new.cpp "int b() { return 2; }\n")
id_of(${WORK}/repo untracked_edited)
expect_differ("an untracked source, edited" "${untracked_edited}" "${untracked}")
file(REMOVE ${WORK}/repo/sweeps/new.cpp)

# ---- edits outside the binary's sources do not make it dirty ------------------------------------
file(WRITE ${WORK}/repo/data/notes.txt "other notes\n")
file(WRITE ${WORK}/repo/README.md "readme\n")
id_of(${WORK}/repo elsewhere)
expect("edits to data and docs" "${elsewhere}" "${first}")

# ---- a commit: the new commit ------------------------------------------------------------------
file(WRITE ${WORK}/repo/lib/a.cpp "int a() { return 4; }\n")
commit_all(second second)
id_of(${WORK}/repo committed)
expect("after a commit" "${committed}" "${second}")

# ---- no git repository ------------------------------------------------------------------------
id_of(${WORK}/plain plain)
expect("a folder outside git" "${plain}" "unknown")

file(REMOVE_RECURSE ${WORK})
message(STATUS "git_id.cmake: every state gives its id")
