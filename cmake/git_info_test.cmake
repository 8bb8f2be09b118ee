# cmake -DSCRIPT=git_info.cmake -DWORK_DIR=... -P git_info_test.cmake: git_info.cmake on a
# scratch repository. A clean tree is not dirty and has no hash; a change to a tracked file makes
# it dirty, with the SHA-256 of `git diff --binary HEAD` outside results/ (checked against
# sha256sum); another change gives another hash, the same change again the same; a change
# inside results/ alone leaves the tree clean. Run by ctest as bench/git_info.
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}/repo/results")
set(repo "${WORK_DIR}/repo")
set(header "${WORK_DIR}/git_info.h")

function(git)
  execute_process(COMMAND git -C "${repo}" -c user.name=test -c user.email=test@example.org
                          ${ARGN}
                  RESULT_VARIABLE status OUTPUT_QUIET ERROR_VARIABLE error)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "git ${ARGN}: ${error}")
  endif()
endfunction()

# Runs git_info.cmake; sets `dirty` and `hash` from the header it writes.
function(read_git_info)
  execute_process(COMMAND "${CMAKE_COMMAND}" -DSOURCE_DIR=${repo} -DOUTPUT=${header}
                          -P "${SCRIPT}" RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "git_info.cmake failed")
  endif()
  file(READ "${header}" text)
  string(REGEX MATCH "kDirty = ([a-z]+);" _ "${text}")
  set(dirty "${CMAKE_MATCH_1}" PARENT_SCOPE)
  string(REGEX MATCH "kDiffSha256 = \"([0-9a-f]*)\";" _ "${text}")
  set(hash "${CMAKE_MATCH_1}" PARENT_SCOPE)
endfunction()

function(expect what actual expected)
  if(NOT "${actual}" STREQUAL "${expected}")
    message(FATAL_ERROR "${what}: expected '${expected}', got '${actual}'")
  endif()
endfunction()

git(init -q)
file(WRITE "${repo}/tracker.cc" "int a = 1;\n")
file(WRITE "${repo}/results/summary.csv" "a\n")
git(add tracker.cc results/summary.csv)
git(commit -q -m first)

read_git_info()
expect("a clean tree: dirty" "${dirty}" "false")
expect("a clean tree: hash" "${hash}" "")

file(WRITE "${repo}/results/summary.csv" "b\n")
read_git_info()
expect("a change in results/ alone: dirty" "${dirty}" "false")

file(WRITE "${repo}/tracker.cc" "int a = 2;\n")
read_git_info()
expect("a changed tracker: dirty" "${dirty}" "true")
execute_process(COMMAND sh -c "git diff --binary HEAD -- . ':!results' | sha256sum"
                WORKING_DIRECTORY "${repo}" OUTPUT_VARIABLE sum)
string(SUBSTRING "${sum}" 0 64 sum)
expect("a changed tracker: hash" "${hash}" "${sum}")
set(first_hash "${hash}")

file(WRITE "${repo}/tracker.cc" "int a = 3;\n")
read_git_info()
if(hash STREQUAL first_hash OR NOT hash MATCHES "^[0-9a-f]+$")
  message(FATAL_ERROR "another change: expected another hash than ${first_hash}, got '${hash}'")
endif()

file(WRITE "${repo}/tracker.cc" "int a = 2;\n")
read_git_info()
expect("the first change again: hash" "${hash}" "${first_hash}")
