# Checks of the project's scripts and docs, registered with CTest (included
# from CMakeLists.txt with the other tests; RB_PYTHON3 is Debian's python3).

# every relative link in README.md and docs/*.md resolves inside the repository
add_test(NAME docs.links
         COMMAND ${RB_PYTHON3} -m unittest discover -s tests/docs -t .
         WORKING_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR})

# the method table of docs/integrators.md is `rollbench list --markdown`
# (scripts/method_table.py writes it; a registry change without it fails here)
add_test(NAME docs.method_table
         COMMAND ${RB_PYTHON3} scripts/method_table.py --check $<TARGET_FILE:rollbench>
         WORKING_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR})

# scripts/slurm/ on a real single-node cluster on localhost; skipped (77)
# without root or without slurm-wlm and munge. Its own waits give up well
# before this timeout, so that it always stops what it started. Once, in the
# release build: the sanitizer build (scripts/robustness.sh) is about the C++.
if(NOT RB_SANITIZE)
  add_test(NAME slurm.cluster
           COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/tests/slurm/test_slurm.sh $<TARGET_FILE:rollbench>)
  set_tests_properties(slurm.cluster PROPERTIES TIMEOUT 600 SKIP_RETURN_CODE 77)
endif()

# the SciPy peer (docs/peers.md): the problem library through ctypes, scored by
# this build's rollbench. Not in the sanitizer build: Python cannot load a
# library built with AddressSanitizer (the C++ test of the library runs there).
if(NOT RB_SANITIZE)
  add_test(NAME analysis.scipy_peer
           COMMAND ${RB_PYTHON3} -m unittest tests.peers.test_scipy_peer
           WORKING_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR})
  set_tests_properties(analysis.scipy_peer PROPERTIES ENVIRONMENT
    "RB_ROLLBENCH=$<TARGET_FILE:rollbench>;RB_PROBLEM_LIB=$<TARGET_FILE:rollbench_problem>")
  # the Octave peer: Debian's octave and liboctave-dev (install-deps.sh --tests)
  add_test(NAME analysis.octave_peer
           COMMAND ${RB_PYTHON3} -m unittest tests.peers.test_octave_peer
           WORKING_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR})
  set_tests_properties(analysis.octave_peer PROPERTIES TIMEOUT 600 ENVIRONMENT
    "RB_ROLLBENCH=$<TARGET_FILE:rollbench>;RB_PROBLEM_LIB=$<TARGET_FILE:rollbench_problem>")
endif()

# the Python of analysis/, tests/ and scripts/ passes flake8 (.flake8 holds
# the settings; Debian's python3-flake8, installed by install-deps.sh --tests)
add_test(NAME lint.python
         COMMAND ${RB_PYTHON3} -m flake8 analysis tests scripts
         WORKING_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR})

# the C and C++ sources follow .clang-format (clang-format-14, installed by
# install-deps.sh --tests); once, in the release build, as it reads only text
if(NOT RB_SANITIZE)
  add_test(NAME lint.format
           COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check-format.sh
           WORKING_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR})
endif()

# scripts/same-results.py (docs/performance.md, "Measuring a change"): a build
# against itself, stand-ins for a changed build, and reports; once, in the
# release build, as it tests the script rather than the C++
if(NOT RB_SANITIZE)
  add_test(NAME scripts.same_results
           COMMAND ${RB_PYTHON3} -m unittest discover -s tests/scripts -t .
           WORKING_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR})
  set_tests_properties(scripts.same_results PROPERTIES ENVIRONMENT "RB_ROLLBENCH=$<TARGET_FILE:rollbench>")
endif()
