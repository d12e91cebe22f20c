# `graspkit run`: arguments reach `arg`, exit statuses (0, os.exit's, 1 with a located traceback,
# 124 after --timeout), --json prints the returned value (print() going to stderr), the sandbox refuses a file outside the
# script's folder until --allow-read names it, and a relative model path is found beside the
# script or under --root.

set(dir ${WORK_DIR}/lua_run)
file(REMOVE_RECURSE ${dir})
file(MAKE_DIRECTORY ${dir}/scripts ${dir}/outside)

function(run_script expected_rc)
  execute_process(COMMAND ${GRASPKIT} run ${ARGN} OUTPUT_VARIABLE out ERROR_VARIABLE err
                  RESULT_VARIABLE rc TIMEOUT 60)
  if(NOT rc EQUAL expected_rc)
    message(FATAL_ERROR "graspkit run ${ARGN}: exit ${rc}, want ${expected_rc}\n${out}\n${err}")
  endif()
  set(out "${out}" PARENT_SCOPE)
  set(err "${err}" PARENT_SCOPE)
endfunction()

function(expect_in text expected)
  string(FIND "${text}" "${expected}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "missing '${expected}' in:\n${text}")
  endif()
endfunction()

# Arguments after -- arrive in arg, in order, and arg[0] is the script.
file(WRITE ${dir}/scripts/args.lua
     "print(#arg, arg[1], arg[2], arg[0]:match('args.lua$') ~= nil)\n")
run_script(0 ${dir}/scripts/args.lua -- first --second)
expect_in("${out}" "2\tfirst\t--second\ttrue")

# An error: exit 1, the message and a traceback naming the file and line.
file(WRITE ${dir}/scripts/fails.lua "local x = 1\nlocal y = x + nil\n")
run_script(1 ${dir}/scripts/fails.lua)
expect_in("${err}" "fails.lua:2: attempt to perform arithmetic on a nil value")
expect_in("${err}" "stack traceback:")

# An engine error raised through the API names the script line and the engine's complaint.
file(WRITE ${dir}/scripts/engine_error.lua "\n\ngraspkit.load_world('missing_world.xml')\n")
run_script(1 ${dir}/scripts/engine_error.lua)
expect_in("${err}" "engine_error.lua:3:")
expect_in("${err}" "missing_world.xml")

# os.exit(n) is the exit status; nothing is lost from stdout.
file(WRITE ${dir}/scripts/exits.lua "print('before exit')\nos.exit(7)\n")
run_script(7 ${dir}/scripts/exits.lua)
expect_in("${out}" "before exit")

# An endless loop, even one that swallows errors with pcall, ends at --timeout with 124.
file(WRITE ${dir}/scripts/forever.lua "while true do pcall(function() while true do end end) end\n")
run_script(124 --timeout 0.5 ${dir}/scripts/forever.lua)
expect_in("${err}" "--timeout")

# --json prints what the script returns, and only that: the script's print() goes to stderr.
file(WRITE ${dir}/scripts/returns.lua
     "print('working on', arg[1])\nreturn {count = #arg, name = arg[1], values = {1.5, 2}}\n")
run_script(0 --json ${dir}/scripts/returns.lua -- mug)
expect_in("${err}" "working on\tmug")
string(FIND "${out}" "working on" printed)
if(NOT printed EQUAL -1)
  message(FATAL_ERROR "--json: the script's print went to stdout:\n${out}")
endif()
string(JSON name GET "${out}" name)
string(JSON second GET "${out}" values 1)
if(NOT name STREQUAL "mug" OR NOT second EQUAL 2)
  message(FATAL_ERROR "--json output: ${out}")
endif()

# The sandbox: a file outside the script's folder is refused, then allowed by --allow-read.
file(WRITE ${dir}/outside/data.txt "secret")
file(WRITE ${dir}/scripts/reads.lua
     "local f = assert(io.open(arg[1])) print(f:read('a')) f:close()\n")
run_script(1 ${dir}/scripts/reads.lua -- ${dir}/outside/data.txt)
expect_in("${err}" "sandbox")
expect_in("${err}" "data.txt")
run_script(0 --allow-read ${dir}/outside ${dir}/scripts/reads.lua -- ${dir}/outside/data.txt)
expect_in("${out}" "secret")
# Writing there still needs --allow-write.
file(WRITE ${dir}/scripts/writes.lua "assert(io.open(arg[1], 'w')):write('x')\n")
run_script(1 --allow-read ${dir}/outside ${dir}/scripts/writes.lua -- ${dir}/outside/new.txt)
if(EXISTS ${dir}/outside/new.txt)
  message(FATAL_ERROR "the sandbox let a script write outside its folders")
endif()
run_script(0 --allow-write ${dir}/outside ${dir}/scripts/writes.lua -- ${dir}/outside/new.txt)

# Relative model paths: found under --root (a model root is readable without --allow-read).
file(WRITE ${dir}/scripts/world.lua
     "local w = graspkit.load_world('worlds/default.xml') print(#w:bodies(), #w:robots())\n")
run_script(0 --root ${SOURCE_DIR}/models ${dir}/scripts/world.lua)
expect_in("${out}" "2\t1")
run_script(1 ${dir}/scripts/world.lua)

# A missing script is a usage error, not a crash.
run_script(2 ${dir}/scripts/no_such_script.lua)
