-- pattern_fuzz.lua: the host's metered matcher (global `bounded`, from lua/lpattern.c)
-- must agree with stock Lua's string.find/match/gmatch/gsub, results and error messages,
-- on random subjects and patterns.  Run by build/lua/pattern_fuzz; prints "N passed, N failed".
local passed, failed = 0, 0
local shown = 0

local function pack(...) return { n = select("#", ...), ... } end

local function same(a, b)
  if a.n ~= b.n then return false end
  for i = 1, a.n do
    if a[i] ~= b[i] then return false end
  end
  return true
end

local function show(t)
  local out = {}
  for i = 1, t.n do out[i] = string.format("%q", t[i]) end
  return "(" .. table.concat(out, ", ") .. ")"
end

local function check(what, f_stock, f_ours, ...)
  local a = pack(pcall(f_stock, ...))
  local b = pack(pcall(f_ours, ...))
  if same(a, b) then
    passed = passed + 1
  else
    failed = failed + 1
    if shown < 20 then
      shown = shown + 1
      print("MISMATCH " .. what .. show(pack(...)))
      print("  stock:   " .. show(a))
      print("  bounded: " .. show(b))
    end
  end
end

local function collect(gmatch, s, p, init)
  local out = {}
  local n = 0
  for a, b, c in gmatch(s, p, init) do
    n = n + 1
    out[#out + 1] = tostring(a) .. "|" .. tostring(b) .. "|" .. tostring(c)
    if n > 200 then break end
  end
  return table.concat(out, ";")
end

local function run(s, p, init, repl)
  check("find", string.find, bounded.find, s, p, init)
  check("find plain", string.find, bounded.find, s, p, init, true)
  check("match", string.match, bounded.match, s, p, init)
  check("gsub", string.gsub, bounded.gsub, s, p, repl)
  check("gsub n", string.gsub, bounded.gsub, s, p, repl, 2)
  check("gmatch", function(...) return collect(string.gmatch, ...) end,
        function(...) return collect(bounded.gmatch, ...) end, s, p, init)
end

-- Hand-picked cases: every construct of the manual's section 6.4.1.
local fixed = {
  { "hello world", "o w" }, { "hello world", "l+" }, { "hello world", "l-o" },
  { "hello", "^h" }, { "hello", "o$" }, { "hello", "^hello$" }, { "a$b", "$b" },
  { "key = value", "(%w+)%s*=%s*(%w+)" }, { "abc", "()b()" }, { "abcabc", "(abc)%1" },
  { "THE (quick) fox", "%((%a+)%)" }, { "f(a(b)c)d", "%b()" }, { "THE (quick) fox", "%f[%a]%a+" },
  { "x = 1.5e10", "[%d%.e]+" }, { "a]b", "[]]" }, { "a-b", "[a-]" }, { "a^b", "[%^]" },
  { "abc", "[^a]+" }, { "\0a\0", "%z" }, { "\0a\0", "a\0" }, { "a.b", "%." },
  { "aaa", "a*" }, { "aaa", "a-" }, { "aaa", "a?a?a?a?" }, { "", "" }, { "", "a*" },
  { "abc", "" }, { "abc", "%" }, { "abc", "[a" }, { "abc", "(a" }, { "abc", "a)" },
  { "abc", "%1" }, { "abc", "%b" }, { "abc", "%f" }, { "abc", "%fa" }, { "abc", "(()" },
  { "ab12CD", "%u+" }, { "ab12CD", "%l+" }, { "ab12 CD", "%S+" }, { "a,b;c", "%p" },
  { "x\tY", "%c" }, { "ff0A", "%x+" }, { "a b", "%g+" }, { "abc", "%W" },
  { "one two three", "(%a+) (%a+)" }, { "abc", "((a)(b))" }, { "aXbXc", "X" },
  { "abc", "b", -1 }, { "abc", "b", -10 }, { "abc", "b", 10 }, { "abc", "", 4 }, { "abc", "", 5 },
  { "hello world from Lua", "%a+", 7 }, { "abc", "^b", 2 },
}
local repls = { "<%0>", "%1-%1", "x", "%%", "%2", "%", "%z", 12,
  { a = "A", hello = 1, world = false }, function(a) return a and a:upper() end,
  function() return {} end }
for _, c in ipairs(fixed) do
  for _, r in ipairs(repls) do run(c[1], c[2], c[3], r) end
end

-- Random cases from a small alphabet that makes matches and malformed patterns likely.
math.randomseed(20240607)
local subject_chars = { "a", "b", "c", "(", ")", "[", "]", "%", ".", "-", " ", "1", "\0", "^", "$", "A" }
local atoms = { "a", "b", ".", "%a", "%d", "%s", "%A", "[ab]", "[^a]", "[a-c]", "[%a%d]", "%%",
  "(", ")", "()", "%1", "%2", "%b()", "%f[%a]", "%f[%A]", "^", "$", "[", "%", "]", "\0", "[]]", "%." }
local quants = { "", "", "", "*", "+", "-", "?" }
local function rnd(t) return t[math.random(#t)] end
for _ = 1, 4000 do
  local s = {}
  for i = 1, math.random(0, 12) do s[i] = rnd(subject_chars) end
  local p = {}
  for i = 1, math.random(0, 5) do p[i] = rnd(atoms) .. rnd(quants) end
  local init = math.random(1, 4) == 1 and math.random(-6, 14) or nil
  run(table.concat(s), table.concat(p), init, rnd(repls))
end

-- The meter sees the work: a pattern bomb costs at least its backtracking.
local before = metered.units()
metered.find(string.rep("a", 300), ".-.-.-b")
local cost = metered.units() - before
if cost > 300 * 300 then passed = passed + 1 else
  failed = failed + 1
  print("meter: a cubic backtrack was charged only " .. cost .. " units")
end

-- A set is read byte by byte each time it is tried: a lazy `.-` before a 256-byte set that
-- never matches tries the set at every pair (start, end) of a 300-byte subject, some 45,000
-- times, reading it twice (parsed and matched), so the meter must see at least a unit per
-- 4 bytes of it each time: 45,000 * 2 * 256 / 4 units (found by fuzz_lua: a 330-byte set
-- along a 60 kB subject ran some 100 times what its units allowed).
local set = "[" .. string.rep("b", 256) .. "]"
before = metered.units()
metered.find(string.rep("a", 300), ".-" .. set)
cost = metered.units() - before
local tries = 300 * 301 / 2
if cost >= tries * 2 * 256 / 4 then passed = passed + 1 else
  failed = failed + 1
  print("meter: " .. tries .. " tries of a 256-byte set were charged only " .. cost .. " units")
end

print(passed .. " passed, " .. failed .. " failed")
if failed > 0 then os.exit(1) end
