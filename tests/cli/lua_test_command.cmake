# `graspkit test` on the fixture files in tests/lua/fixtures/, whose outcomes are known by
# reading them: which tests pass, fail (at which line, with which message) or are skipped.
cmake_policy(VERSION 3.20)  # quoted if() arguments are strings, not variable names
set(fixtures ${SOURCE_DIR}/tests/lua/fixtures)
file(MAKE_DIRECTORY ${WORK_DIR})

# Runs graspkit in the fixtures folder (so file names print as given); sets out, err and rc.
macro(graspkit_test)
  execute_process(COMMAND ${GRASPKIT} ${ARGN} WORKING_DIRECTORY ${fixtures}
                  OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
endmacro()

function(expect_status expected)
  if(NOT rc EQUAL expected)
    message(FATAL_ERROR "expected exit status ${expected}, got ${rc}\nstdout:\n${out}\nstderr:\n${err}")
  endif()
endfunction()

# Each argument must appear in stdout as plain text.
function(expect_output)
  foreach(text ${ARGN})
    string(FIND "${out}" "${text}" at)
    if(at EQUAL -1)
      message(FATAL_ERROR "expected in the output: '${text}'\nstdout:\n${out}\nstderr:\n${err}")
    endif()
  endforeach()
endfunction()

function(expect_no_output text)
  string(FIND "${out}" "${text}" at)
  if(NOT at EQUAL -1)
    message(FATAL_ERROR "unexpected in the output: '${text}'\nstdout:\n${out}")
  endif()
endfunction()

function(expect_closing_line line)
  if(NOT out MATCHES "\n${line}\n$")
    message(FATAL_ERROR "expected the closing line '${line}'\nstdout:\n${out}\nstderr:\n${err}")
  endif()
endfunction()

function(expect_count text pattern expected what)
  string(REGEX MATCHALL "${pattern}" found "${text}")
  list(LENGTH found count)
  if(NOT count EQUAL expected)
    message(FATAL_ERROR "${what}: expected ${expected}, found ${count}\n${text}")
  endif()
endfunction()

# Every expectation holds.
graspkit_test(test passing.lua)
expect_status(0)
expect_count("${out}" "\nPASS  passing.lua: " 5 "PASS lines after the first")
expect_output("PASS  passing.lua: deep equality (")
expect_closing_line("6 passed, 0 failed")

# A failing expect_near on line 5; the other test passes.
graspkit_test(test near_failure.lua)
expect_status(1)
expect_output("PASS  near_failure.lua: holds ("
              "FAIL  near_failure.lua: misses ("
              "\n    near_failure.lua:5: expect_near: 3.2 vs 3.0 (tolerance 0.1)\n")
expect_closing_line("1 passed, 1 failed")

# An error inside a test fails it with the message and a traceback; the next test still runs.
graspkit_test(test error_inside.lua)
expect_status(1)
expect_output("FAIL  error_inside.lua: raises ("
              "    error_inside.lua:3: attempt to index a nil value (local 't')\n    stack traceback:\n"
              "PASS  error_inside.lua: runs after an error (")
expect_closing_line("1 passed, 1 failed")

# A file that does not load is one failed test named after the file.
graspkit_test(test syntax_error.lua)
expect_status(1)
expect_output("FAIL  syntax_error.lua (" "    syntax_error.lua:4: ')' expected")
expect_closing_line("0 passed, 1 failed")

# skip() ends a test as skipped; a failure recorded before it still fails the test.
graspkit_test(test skipping.lua)
expect_status(1)
expect_output("SKIP  skipping.lua: skipped (needs a robot)\n"
              "FAIL  skipping.lua: failed before skip (" "    skipping.lua:7: expect_true: got false\n"
              "PASS  skipping.lua: passes (")
expect_no_output("not reached")
expect_closing_line("1 passed, 1 failed, 1 skipped")

# skip() at the top level skips the whole file; nothing failed, so the status is 0.
graspkit_test(test skipped_file.lua)
expect_status(0)
expect_output("SKIP  skipped_file.lua (nothing to test here)\n")
expect_closing_line("0 passed, 0 failed, 1 skipped")

# An expectation outside any test fails the file's entry; its tests still run.
graspkit_test(test top_level_failure.lua)
expect_status(1)
expect_output("FAIL  top_level_failure.lua (" "    top_level_failure.lua:1: expect_equal: 1 vs 2\n"
              "PASS  top_level_failure.lua: still runs (")
expect_closing_line("1 passed, 1 failed")

graspkit_test(test duplicate.lua)
expect_status(1)
expect_output("    duplicate.lua:2: test \"a\" is already defined at line 1\n")

# The time limit applies to each test, and the test after a timed-out one runs.
graspkit_test(test --timeout 0.5 timeout.lua)
expect_status(1)
expect_output("FAIL  timeout.lua: spins (" "time limit of 0.5 s exceeded"
              "PASS  timeout.lua: runs after the time limit (")
expect_closing_line("1 passed, 1 failed")

# A folder: only *_test.lua files, recursively, sorted, each in its own Lua state (b_test.lua
# does not see the global a_test.lua set).
graspkit_test(test folder)
expect_status(0)
if(NOT out MATCHES "^PASS  folder/a_test.lua: a \\([0-9]+ ms\\)\nPASS  folder/sub/b_test.lua: b sees no global from a_test.lua \\(")
  message(FATAL_ERROR "folder: ${out}")
endif()
expect_no_output("helper")
expect_no_output("txt")
expect_closing_line("2 passed, 0 failed")

# Errors: a missing path, no test files, no tests, a --junit folder that does not exist.
graspkit_test(test passing.lua nope.lua)
expect_status(1)
if(NOT err MATCHES "nope.lua: no such file or folder")
  message(FATAL_ERROR "missing path: ${err}")
endif()
file(MAKE_DIRECTORY ${WORK_DIR}/no_test_files)
graspkit_test(test ${WORK_DIR}/no_test_files)
expect_status(1)
if(NOT err MATCHES "no test files \\(\\*_test.lua\\) found in")
  message(FATAL_ERROR "empty folder: ${err}")
endif()
graspkit_test(test no_tests.lua)
expect_status(1)
if(NOT err MATCHES "no tests found")
  message(FATAL_ERROR "no tests: ${err}")
endif()
graspkit_test(test --junit ${WORK_DIR}/no/such/folder/report.xml passing.lua)
expect_status(1)
if(NOT err MATCHES "--junit: no such folder" OR NOT out STREQUAL "")
  message(FATAL_ERROR "--junit folder: ${out}${err}")
endif()

# --quiet prints the failed tests and the closing line only.
graspkit_test(-q test passing.lua near_failure.lua)
expect_status(1)
expect_no_output("PASS")
expect_output("FAIL  near_failure.lua: misses (")
expect_closing_line("7 passed, 1 failed")

# print() goes to stdout, and to stderr under --json so the report stays parseable.
graspkit_test(test printing.lua)
expect_output("hello from a test\nPASS  printing.lua: prints (")
graspkit_test(test --json printing.lua)
string(JSON passed GET "${out}" passed)
if(NOT passed EQUAL 1 OR NOT err MATCHES "hello from a test")
  message(FATAL_ERROR "print under --json: ${out}\n${err}")
endif()

# The expectation messages, through --json. expectations.lua fails each test in a known way.
graspkit_test(test --json expectations.lua)
expect_status(1)
function(expect_failure test index kind line message)
  string(JSON name GET "${out}" files 0 tests ${test} name)
  string(JSON got_kind GET "${out}" files 0 tests ${test} failures ${index} kind)
  string(JSON got_message GET "${out}" files 0 tests ${test} failures ${index} message)
  if(kind STREQUAL "expectation")
    string(JSON got_line GET "${out}" files 0 tests ${test} failures ${index} line)
    string(JSON got_file GET "${out}" files 0 tests ${test} failures ${index} file)
  else()
    set(got_line "${line}")
    set(got_file "expectations.lua")
  endif()
  if(NOT got_kind STREQUAL kind OR NOT got_line EQUAL line OR NOT got_file STREQUAL "expectations.lua"
     OR NOT got_message STREQUAL message)
    message(FATAL_ERROR "test '${name}' failure ${index}: expected ${kind} at line ${line}: '${message}'\n"
                        "got ${got_kind} ${got_file}:${got_line}: '${got_message}'")
  endif()
endfunction()
expect_failure(0 0 expectation 6 "expect_equal: at [2].x: 2 vs 3")
expect_failure(1 0 expectation 7 "expect_equal: at .b: nil vs 2")
expect_failure(2 0 expectation 8 "expect_near: at [2]: 2.5 vs 2 (tolerance 0.1)")
expect_failure(3 0 expectation 9 "expect_near: at [3]: 3 vs nil (tolerance 0.1)")
expect_failure(4 0 expectation 10 "expect_equal: 0.30000000000000004 vs 0.3")
expect_failure(5 0 expectation 11 "expect_error: no error raised")
expect_failure(6 0 expectation 12 "expect_error: \"bang\" not found in the error: boom")
expect_failure(7 0 expectation 13 "expect_true: got nil: the hand is open")
expect_failure(8 0 expectation 15 "expect_false: got 1")
expect_failure(8 1 expectation 16 "expect_nil: got \"x\"")
expect_failure(8 2 expectation 17 "fail: by hand")
expect_failure(9 0 expectation 3 "expect_equal: \"a\" vs \"b\"")  # inside the helper
expect_failure(10 0 expectation 20 "expect_equal: \"a\\nb\" vs \"a\"")
expect_failure(11 0 error 0 "expectations.lua:21: expect_near(actual, expected, tolerance): tolerance must be a number >= 0")
string(JSON tests LENGTH "${out}" files 0 tests)
string(JSON failed GET "${out}" failed)
if(NOT tests EQUAL 12 OR NOT failed EQUAL 12)
  message(FATAL_ERROR "expectations.lua: ${tests} tests, ${failed} failed")
endif()

# Five files at once: the closing line, the JSON report and the JUnit XML agree with the counts
# above: 6 + 2 + 2 + 1 + 3 = 14 tests; passed 6 + 1 + 1 + 0 + 1 = 9; failed 0 + 1 + 1 + 1 + 1 = 4;
# skipped 1.
set(five passing.lua near_failure.lua error_inside.lua syntax_error.lua skipping.lua)
set(junit ${WORK_DIR}/lua_test_report.xml)
file(REMOVE ${junit})
graspkit_test(test --junit ${junit} ${five})
expect_status(1)
expect_closing_line("9 passed, 4 failed, 1 skipped")
file(READ ${junit} xml)
expect_count("${xml}" "<testsuite " 5 "JUnit testsuite elements")
expect_count("${xml}" "<testcase " 14 "JUnit testcase elements")
expect_count("${xml}" "<failure " 4 "JUnit failure elements")
expect_count("${xml}" "<skipped" 1 "JUnit skipped elements")
foreach(text "<testsuites name=\"graspkit test\" tests=\"14\" failures=\"4\" errors=\"0\" skipped=\"1\""
             "<testsuite name=\"near_failure.lua\" tests=\"2\" failures=\"1\" errors=\"0\" skipped=\"0\""
             "<testcase classname=\"near_failure.lua\" name=\"misses\""
             "<failure message=\"near_failure.lua:5: expect_near: 3.2 vs 3.0 (tolerance 0.1)\" type=\"expectation\">"
             "<testcase classname=\"syntax_error.lua\" name=\"syntax_error.lua\""
             "<skipped message=\"needs a robot\"/>")
  string(FIND "${xml}" "${text}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "expected in the JUnit report: ${text}\n${xml}")
  endif()
endforeach()
file(GLOB leftovers ${WORK_DIR}/lua_test_report.xml.tmp*)
if(leftovers)
  message(FATAL_ERROR "temporary report files left: ${leftovers}")
endif()

graspkit_test(test --json ${five})
expect_status(1)
string(JSON files LENGTH "${out}" files)
string(JSON passed GET "${out}" passed)
string(JSON failed GET "${out}" failed)
string(JSON skipped GET "${out}" skipped)
string(JSON status GET "${out}" files 3 tests 0 status)
string(JSON whole GET "${out}" files 3 tests 0 whole_file)
string(JSON reason GET "${out}" files 4 tests 0 skip_reason)
if(NOT files EQUAL 5 OR NOT passed EQUAL 9 OR NOT failed EQUAL 4 OR NOT skipped EQUAL 1
   OR NOT status STREQUAL "failed" OR NOT whole STREQUAL "ON" OR NOT reason STREQUAL "needs a robot")
  message(FATAL_ERROR "--json: ${files} files, ${passed}/${failed}/${skipped}, ${status} ${whole} ${reason}\n${out}")
endif()
