-- graspkit's scenario test library. `graspkit test` runs this chunk in each test file's Lua
-- state before the file itself; it installs the globals test, skip, fail and expect_* and
-- returns the harness through which the host (scripting/src/test_runner.cpp) runs the tests.
--
-- The one argument is `where`, a C function that returns the file and line of the innermost
-- call made from outside this chunk: the line of the expect_ call in the test file. (The
-- sandbox removes the debug library, so the host provides this.)
--
-- Expectations are non-fatal, like GoogleTest's EXPECT_*: a failure is recorded with its file
-- and line and the test goes on. Each returns true when it held.

local where = ...

local tests = {}    -- {name =, fn =, line =} in the order test() registered them
local defined = {}  -- name -> line, to refuse duplicates
local current       -- the record of what runs now: {failures = {}, skip = reason or nil}
local SKIP = {}     -- the error value skip() raises to end a test

---------------------------------------------------------------------------------------------
-- Showing values in messages

local show

-- Lua's own float format (%.14g) can print two different numbers alike ("0.3 vs 0.3"); use
-- the shortest of 15 or 17 digits that reads back as the same number.
local function show_float(x)
  if x ~= x or x == math.huge or x == -math.huge then return tostring(x) end
  local text = string.format("%.15g", x)
  if tonumber(text) ~= x then text = string.format("%.17g", x) end
  if not text:find("[.e]") then text = text .. ".0" end
  return text
end

local function sorted_keys(...)
  local keys, seen = {}, {}
  for i = 1, select("#", ...) do
    local t = select(i, ...)
    if type(t) == "table" then
      for k in next, t do
        if not seen[k] then
          seen[k] = true
          keys[#keys + 1] = k
        end
      end
    end
  end
  -- Numbers first in order, then strings in order, then the rest by their text.
  local rank = {number = 1, string = 2}
  table.sort(keys, function(a, b)
    local ra, rb = rank[type(a)] or 3, rank[type(b)] or 3
    if ra ~= rb then return ra < rb end
    if ra == 3 then return tostring(a) < tostring(b) end
    return a < b
  end)
  return keys
end

local function key_text(k)
  if type(k) == "string" and k:match("^[%a_][%w_]*$") then return "." .. k end
  return "[" .. show(k) .. "]"
end

local MAX_ITEMS = 10  -- a long table is cut after this many entries
local MAX_DEPTH = 3
local MAX_STRING = 200  -- and a long string after this many bytes

local function show_table(t, depth)
  if depth > MAX_DEPTH then return "{...}" end
  local parts = {}
  local count = 0
  local n = #t
  for i = 1, n do
    count = count + 1
    if count > MAX_ITEMS then break end
    parts[#parts + 1] = show(rawget(t, i), depth + 1)
  end
  for _, k in ipairs(sorted_keys(t)) do
    if not (math.type(k) == "integer" and k >= 1 and k <= n) then
      count = count + 1
      if count > MAX_ITEMS then break end
      local name = (type(k) == "string" and k:match("^[%a_][%w_]*$")) and k or ("[" .. show(k) .. "]")
      parts[#parts + 1] = name .. " = " .. show(rawget(t, k), depth + 1)
    end
  end
  if count > MAX_ITEMS then parts[#parts + 1] = "..." end
  return "{" .. table.concat(parts, ", ") .. "}"
end

show = function(v, depth)
  local kind = type(v)
  if kind == "string" then
    local cut = #v > MAX_STRING and string.format("...(%d bytes)", #v) or ""
    return (string.format("%q", v:sub(1, MAX_STRING)):gsub("\\\n", "\\n")) .. cut
  end
  if math.type(v) == "float" then return show_float(v) end
  if kind == "table" then
    local meta = getmetatable(v)
    -- A locked metatable (graspkit's poses) shows as its class name: the class prints itself.
    if type(meta) == "string" or (type(meta) == "table" and rawget(meta, "__tostring")) then
      return tostring(v)
    end
    return show_table(v, depth or 1)
  end
  return tostring(v)
end

---------------------------------------------------------------------------------------------
-- Comparisons. Each returns nil when the values match, else the path to the first mismatch
-- and the two values there.

-- Deep equality: tables match when they have the same keys with matching values (metatables
-- are not compared); anything else compares with == (so 1 matches 1.0 and NaN matches nothing).
local function difference(a, b, path, seen)
  if rawequal(a, b) then return nil end
  if type(a) ~= "table" or type(b) ~= "table" then
    if a == b then return nil end
    return path, a, b
  end
  if seen[a] == b then return nil end  -- a cycle: this pair is being compared further up
  seen[a] = b
  for _, k in ipairs(sorted_keys(a, b)) do
    local where_, x, y = difference(rawget(a, k), rawget(b, k), path .. key_text(k), seen)
    if where_ then return where_, x, y end
  end
  return nil
end

-- Like difference(), but numbers match when they differ by at most `tolerance`.
local function outside(actual, expected, tolerance, path)
  if type(expected) == "number" and type(actual) == "number" then
    if math.abs(actual - expected) <= tolerance then return nil end
    return path, actual, expected
  end
  if type(expected) == "table" and type(actual) == "table" then
    for _, k in ipairs(sorted_keys(actual, expected)) do
      local where_, x, y = outside(rawget(actual, k), rawget(expected, k), tolerance, path .. key_text(k))
      if where_ then return where_, x, y end
    end
    return nil
  end
  return difference(actual, expected, path, {})
end

---------------------------------------------------------------------------------------------
-- Recording

local function check_running(name)
  if current == nil then error(name .. "() called while no test file or test runs", 3) end
end

-- Records a failure at the caller's file and line. `note` is the user's optional message.
local function record(text, note)
  if note ~= nil then text = text .. ": " .. tostring(note) end
  local file, line = where()
  current.failures[#current.failures + 1] = {file = file, line = line, message = text}
  return false
end

local function at(path)
  return path ~= "" and ("at " .. path .. ": ") or ""
end

---------------------------------------------------------------------------------------------
-- The globals

function test(name, fn)
  check_running("test")
  if current.name ~= nil then error("test() inside a test: tests are defined at the top level", 2) end
  if type(name) ~= "string" or name == "" then error("test(name, fn): name must be a non-empty string", 2) end
  if type(fn) ~= "function" then error("test(name, fn): fn must be a function", 2) end
  local _, line = where()
  if defined[name] then
    error(string.format("test %q is already defined at line %d", name, defined[name]), 2)
  end
  defined[name] = line
  tests[#tests + 1] = {name = name, fn = fn, line = line}
end

-- Ends the running test (or, at the top level, the whole file) as skipped.
function skip(reason)
  check_running("skip")
  if reason ~= nil and type(reason) ~= "string" then error("skip(reason): reason must be a string", 2) end
  current.skip = reason or ""
  error(SKIP, 0)
end

function fail(note)
  check_running("fail")
  return record("fail", note)
end

function expect_true(value, note)
  check_running("expect_true")
  if value then return true end
  return record("expect_true: got " .. show(value), note)
end

function expect_false(value, note)
  check_running("expect_false")
  if not value then return true end
  return record("expect_false: got " .. show(value), note)
end

function expect_nil(value, note)
  check_running("expect_nil")
  if value == nil then return true end
  return record("expect_nil: got " .. show(value), note)
end

function expect_not_nil(value, note)
  check_running("expect_not_nil")
  if value ~= nil then return true end
  return record("expect_not_nil: got nil", note)
end

function expect_equal(actual, expected, note)
  check_running("expect_equal")
  local path, a, e = difference(actual, expected, "", {})
  if path == nil then return true end
  return record(string.format("expect_equal: %s%s vs %s", at(path), show(a), show(e)), note)
end

function expect_not_equal(actual, unexpected, note)
  check_running("expect_not_equal")
  if difference(actual, unexpected, "", {}) ~= nil then return true end
  return record("expect_not_equal: both are " .. show(actual), note)
end

function expect_near(actual, expected, tolerance, note)
  check_running("expect_near")
  if type(tolerance) ~= "number" or not (tolerance >= 0) then
    error("expect_near(actual, expected, tolerance): tolerance must be a number >= 0", 2)
  end
  local path, a, e = outside(actual, expected, tolerance, "")
  if path == nil then return true end
  return record(string.format("expect_near: %s%s vs %s (tolerance %s)", at(path), show(a), show(e),
                              show(tolerance)), note)
end

-- fn must raise an error whose message contains `pattern` (plain text, not a Lua pattern).
-- Returns whether it did and the error message.
function expect_error(fn, pattern, note)
  check_running("expect_error")
  if pattern ~= nil and type(pattern) ~= "string" then
    error("expect_error(fn, pattern): pattern must be a string", 2)
  end
  local meta = getmetatable(fn)
  if type(fn) ~= "function" and not (type(meta) == "table" and rawget(meta, "__call")) then
    error("expect_error(fn, pattern): fn must be a function", 2)
  end
  local ok, err = pcall(fn)
  if not ok and rawequal(err, SKIP) then error(SKIP, 0) end
  if ok then return record("expect_error: no error raised", note), nil end
  local message = type(err) == "string" and err or show(err)
  if pattern ~= nil and not message:find(pattern, 1, true) then
    return record(string.format("expect_error: %q not found in the error: %s", pattern, message), note),
           message
  end
  return true, message
end

-- os.exit would end the whole file from inside one test; a test reports through expectations.
if os then
  os.exit = function() error("os.exit() is not available in a test file", 2) end
end

---------------------------------------------------------------------------------------------
-- The harness the host drives

local harness = {tests = tests}

-- Begins recording for the test named `name`, or for the file's top-level chunk when nil.
function harness.start(name)
  current = {name = name, failures = {}}
end

-- Ends recording; returns the failures ({file, line, message} each) and the skip reason (nil
-- when not skipped).
function harness.finish()
  local record_ = current
  current = nil
  return record_.failures, record_.skip
end

return harness
