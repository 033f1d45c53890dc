-- run.lua: every Lua test of rigid, run by `make test` with stock lua5.4.
--   1. tests/lua/test_rigid.lua, test_gameplay.lua, test_snapshot.lua and test_errors.lua in
--      the sandboxed host and in stock lua5.4 (build/rigid.so);
--   2. tests/lua/pattern_fuzz.lua: the host's metered matcher against stock Lua's;
--   3. tests/lua/hostile/*.lua: each must fail in the host with a clear error (its
--      "-- expect:" lines), file:line and a traceback, exit status 1 (not a crash), and
--      leave the canary file it attacks untouched;
--   4. tests/lua/ok/*.lua: scripts that must run in the host and exit 0;
--   5. lua/examples/*.lua: each runs in the host and draws its picture (and a pile at 1 and
--      3 threads gives one hash);
--   6. with --library: the API tests again in LuaJIT through lua/rigid_jit.lua
--      (with its scalar declarations of the vector calls, and with the header's own), and
--      the LOVE game lua/examples/love headless, whose screenshot must show the player
--      where the physics put it.  What is not installed is skipped, with a line saying so.
-- Closes with "N passed, N failed".
local opts = { lua = "lua5.4", out = "build/lua-tests", ["lua-env"] = "", luajit = "luajit",
               love = "love" }
do
  local i = 1
  while i <= #arg do
    local k = arg[i]:match("^%-%-(.+)$")
    if not k or arg[i + 1] == nil then error("usage: run.lua --host H --module-dir D --fuzz F [--lua L] [--out O] [--lua-env E] [--library LIB [--luajit J] [--love L]]") end
    opts[k] = arg[i + 1]
    i = i + 2
  end
end
assert(opts.host and opts["module-dir"] and opts.fuzz, "run.lua: --host, --module-dir and --fuzz are required")

local passed, failed = 0, 0

local function q(s) return "'" .. tostring(s):gsub("'", "'\\''") .. "'" end

local function run(cmd)
  local p = io.popen(cmd .. " 2>&1")
  local out = p:read("a")
  local _, how, code = p:close()
  return out, how, code
end

local function result(ok, name, detail)
  if ok then
    passed = passed + 1
    print("ok    " .. name)
  else
    failed = failed + 1
    print("FAIL  " .. name .. (detail and ("\n" .. detail:gsub("\n*$", ""):gsub("\n", "\n      ")) or ""))
  end
end

local function read(path)
  local f = io.open(path, "rb")
  if not f then return nil end
  local s = f:read("a")
  f:close()
  return s
end

local function write(path, s)
  local f = assert(io.open(path, "wb"))
  f:write(s)
  f:close()
end

local function list(pattern)
  local out = run("ls " .. pattern .. " 2>/dev/null")
  local t = {}
  for line in out:gmatch("[^\n]+") do t[#t + 1] = line end
  table.sort(t)
  return t
end

os.execute("mkdir -p " .. q(opts.out) .. " " .. q(opts.out .. "/examples"))
local stock = opts["lua-env"] .. " LUA_CPATH=" .. q(opts["module-dir"] .. "/?.so") .. " " .. opts.lua

-- Suites that count their own tests and close with "N passed, N failed".
local function suite(name, cmd, as_one)
  local out, how, code = run(cmd)
  local p, f = out:match("(%d+) passed, (%d+) failed%s*$")
  if not p then
    p, f = out:match("(%d+) passed, (%d+) failed")
  end
  p, f = tonumber(p), tonumber(f)
  io.write((out:gsub("rigid: [^\n]*steps %([^\n]*\n", "")))
  if p and how == "exit" and (code == 0) == (f == 0) then
    if as_one then          -- many comparisons, one test
      passed = passed + (f == 0 and 1 or 0)
      failed = failed + (f == 0 and 0 or 1)
    else
      passed = passed + p
      failed = failed + f
    end
    print(string.format("%-5s %s: %d passed, %d failed", f == 0 and "ok" or "FAIL", name, p, f))
  else
    result(false, name, "no closing count, or exit " .. tostring(how) .. " " .. tostring(code))
  end
end

-- The API tests: the core API, the gameplay collision API, snapshots and the error messages,
-- one script each.
local API_TESTS = { "tests/lua/test_rigid.lua", "tests/lua/test_gameplay.lua",
                    "tests/lua/test_snapshot.lua", "tests/lua/test_errors.lua" }

print("-- API tests in the sandboxed host")
for _, t in ipairs(API_TESTS) do suite("host " .. t, q(opts.host) .. " " .. t) end
print("-- API tests in stock " .. opts.lua)
for _, t in ipairs(API_TESTS) do suite("stock " .. t, stock .. " " .. t) end
print("-- metered pattern matcher against stock Lua")
suite("pattern fuzz (one test)", q(opts.fuzz) .. " tests/lua/pattern_fuzz.lua", true)

print("-- the module exports luaopen_rigid and nothing else")
do
  local out, how, code = run("nm -D --defined-only " .. q(opts["module-dir"] .. "/rigid.so"))
  if how == "exit" and code == 0 then
    local names = {}
    for name in out:gmatch("%S+%s+%a%s+(%S+)") do names[#names + 1] = name end
    result(#names == 1 and names[1] == "luaopen_rigid", "rigid.so exports: " .. table.concat(names, " "))
  else
    print("skip  exports (no nm)")
  end
end

print("-- hostile scripts in the host")
local canary = opts.out .. "/canary.txt"
-- A hang must fail the test, not stall `make test`.
local limit = run("command -v timeout") ~= "" and "timeout 300 " or ""
for _, path in ipairs(list("tests/lua/hostile/*.lua")) do
  local src = read(path)
  local name = path:match("([^/]+)%.lua$")
  local expects, args = {}, ""
  for e in src:gmatch("%-%- expect: ([^\n]+)") do expects[#expects + 1] = e end
  args = (src:match("%-%- args: ([^\n]+)") or ""):gsub("%$OUT", opts.out)
  local want_traceback = not src:find("-- traceback: no", 1, true)
  write(canary, "canary " .. name)
  local out, how, code = run(limit .. q(opts.host) .. " " .. q(path) .. " " .. args .. " -- " .. q(canary))
  local problems = {}
  if how ~= "exit" or code ~= 1 then
    problems[#problems + 1] = "exit: " .. tostring(how) .. " " .. tostring(code) .. " (want exit 1)"
  end
  for _, e in ipairs(expects) do
    if not out:find(e, 1, true) then problems[#problems + 1] = "missing: " .. e end
  end
  if not out:find(name .. ".lua:%d+") then problems[#problems + 1] = "no file:line of the script" end
  if want_traceback and not out:find("stack traceback:", 1, true) then
    problems[#problems + 1] = "no traceback"
  end
  if read(canary) ~= "canary " .. name then problems[#problems + 1] = "the canary file was changed" end
  if out:find("AddressSanitizer", 1, true) or out:find("runtime error:", 1, true) then
    problems[#problems + 1] = "sanitizer report"
  end
  result(#problems == 0, "hostile " .. name,
         #problems > 0 and (table.concat(problems, "\n") .. "\n--- output:\n" .. out:sub(1, 1500)) or nil)
end

print("-- scripts that must run cleanly in the host")
for _, path in ipairs(list("tests/lua/ok/*.lua")) do
  local out, how, code = run(limit .. q(opts.host) .. " " .. q(path) .. " --steps 30")
  result(how == "exit" and code == 0, "runs " .. path, out:sub(1, 1500))
end

print("-- the host's --threads: the same bits as one thread")
do
  local path = "tests/lua/threads/pile.lua"
  local one, how1, code1 = run(q(opts.host) .. " " .. q(path) .. " --threads 1")
  local three, how3, code3 = run(q(opts.host) .. " " .. q(path) .. " --threads 3")
  local h1, h3 = one:match("hash (%x+)"), three:match("hash (%x+)")
  result(how1 == "exit" and code1 == 0 and how3 == "exit" and code3 == 0 and h1 ~= nil and h1 == h3,
         path .. " at 1 and 3 threads: hash " .. tostring(h1) .. " and " .. tostring(h3),
         "--- 1 thread:\n" .. one:sub(1, 800) .. "\n--- 3 threads:\n" .. three:sub(1, 800))
  local bad = run(q(opts.host) .. " " .. q(path) .. " --threads 65")
  result(bad:find("--threads wants a whole number in [1, 64]", 1, true) ~= nil, "--threads 65 is refused", bad)
end

print("-- the host's --timeout: a time limit per call into the script, besides the budget")
do
  local path = "tests/lua/timeout/slow.lua"
  local out, how, code = run(limit .. q(opts.host) .. " " .. q(path) .. " --timeout 0.05")
  result(how == "exit" and code == 1 and out:find("slow.lua:%d+: time limit exceeded %(0.05") ~= nil,
         path .. " --timeout 0.05 stops at the limit, where its budget would not", out:sub(1, 800))
  out, how, code = run(limit .. q(opts.host) .. " " .. q(path) .. " --timeout 0")
  result(how == "exit" and code == 0 and out:find("lookups 40000", 1, true) ~= nil,
         path .. " --timeout 0 runs to its end", out:sub(1, 800))
  local bad = run(q(opts.host) .. " " .. q(path) .. " --timeout -1")
  result(bad:find("--timeout wants a number of seconds >= 0", 1, true) ~= nil, "--timeout -1 is refused", bad)
end

print("-- examples in the host, each drawing its picture")
for _, path in ipairs(list("lua/examples/*.lua")) do
  local name = path:match("([^/]+)%.lua$")
  local svg = opts.out .. "/examples/" .. name .. ".svg"
  os.remove(svg)
  local out, how, code = run(q(opts.host) .. " " .. q(path) .. " --svg " .. q(svg))
  local pic = read(svg) or ""
  local problems = {}
  if how ~= "exit" or code ~= 0 then problems[#problems + 1] = "exit " .. tostring(code) end
  if not (pic:find("^<%?xml") and pic:find("</svg>%s*$")) then problems[#problems + 1] = "no complete SVG" end
  if not (pic:find("<polyline", 1, true) and (pic:find("<circle", 1, true) or pic:find("<rect x", 1, true))) then
    problems[#problems + 1] = "the SVG draws no trail or body"
  end
  result(#problems == 0, "example " .. name .. " -> " .. svg,
         #problems > 0 and (table.concat(problems, "\n") .. "\n--- output:\n" .. out:sub(1, 1500)) or nil)
end

local function installed(cmd) return cmd ~= "" and run("command -v " .. q(cmd)) ~= "" end

-- The player in the screenshot: the pixels of its colour (only the player has it) form the
-- box the physics gives, mapped by the game's own transform, to rasterization (a filled
-- pixel is one whose centre is inside: its centre is within 1/2 pixel of the box's edges,
-- so the centroid is within 1/2 pixel of the box's centre, and each side within 1 pixel).
local function check_shot(dir)
  local rec = {}
  for k, v in (read(dir .. "/shot.txt") or ""):gmatch("([%w_]+) ([^\n]+)") do rec[k] = v end
  local pam = read(dir .. "/shot.pam")
  if not (pam and rec.x) then return false, "no screenshot or no shot.txt in " .. dir end
  local w, h = pam:match("^P7\nWIDTH (%d+)\nHEIGHT (%d+)\nDEPTH 4\nMAXVAL 255\n")
  local body = pam:find("ENDHDR\n", 1, true)
  w, h = tonumber(w), tonumber(h)
  if not (w and body) or #pam - (body + 6) ~= w * h * 4 then return false, "not an RGBA PAM of its size" end
  body = body + 7
  local r0, g0, b0 = rec.color:match("(%d+) (%d+) (%d+)")
  r0, g0, b0 = tonumber(r0), tonumber(g0), tonumber(b0)
  local n, sx, sy, x0, x1, y0, y1 = 0, 0, 0, math.huge, -math.huge, math.huge, -math.huge
  local others = {}
  for j = 0, h - 1 do
    local row = pam:sub(body + j * w * 4, body + (j + 1) * w * 4 - 1)
    for i = 0, w - 1 do
      local r, g, b = row:byte(i * 4 + 1, i * 4 + 3)
      if math.abs(r - r0) <= 2 and math.abs(g - g0) <= 2 and math.abs(b - b0) <= 2 then
        n, sx, sy = n + 1, sx + i + 0.5, sy + j + 0.5
        x0, x1, y0, y1 = math.min(x0, i), math.max(x1, i + 1), math.min(y0, j), math.max(y1, j + 1)
      else
        others[r * 65536 + g * 256 + b] = true
      end
    end
  end
  local colours = 0
  for _ in pairs(others) do colours = colours + 1 end
  local scale, ox, oy = tonumber(rec.scale), tonumber(rec.ox), tonumber(rec.oy)
  local cx, cy = ox + tonumber(rec.x) * scale, oy - tonumber(rec.y) * scale
  local hw, hh = tonumber(rec.half_width) * scale, tonumber(rec.half_height) * scale
  local problems = {}
  if n == 0 then return false, "no pixel of the player's colour" end
  if math.abs(sx / n - cx) > 0.5 or math.abs(sy / n - cy) > 0.5 then
    problems[#problems + 1] = string.format("player drawn around (%.1f, %.1f), the physics says (%.1f, %.1f)",
                                            sx / n, sy / n, cx, cy)
  end
  for _, e in ipairs{ { x0, cx - hw }, { x1, cx + hw }, { y0, cy - hh }, { y1, cy + hh } } do
    if math.abs(e[1] - e[2]) > 1 then
      problems[#problems + 1] = string.format("box [%d, %d] x [%d, %d], the physics says [%.1f, %.1f] x [%.1f, %.1f]",
                                              x0, x1, y0, y1, cx - hw, cx + hw, cy - hh, cy + hh)
      break
    end
  end
  if n ~= (x1 - x0) * (y1 - y0) then problems[#problems + 1] = "the player's pixels are not one filled box" end
  if colours < 4 then problems[#problems + 1] = "a picture of " .. colours .. " other colours: the scene is not drawn" end
  return #problems == 0, table.concat(problems, "\n") .. string.format(" (t = %s s, %d pixels)", rec.t, n)
end

if opts.library then
  print("-- API tests in LuaJIT through lua/rigid_jit.lua")
  local jit_env = opts["lua-env"] .. " LUA_PATH='lua/?.lua;;' RIGID_LIBRARY=" .. q(opts.library)
  if not installed(opts.luajit) then
    print("skip  LuaJIT tests: no " .. opts.luajit .. " (tools/install-deps.sh installs luajit)")
  else
    for _, t in ipairs(API_TESTS) do
      suite("luajit " .. t, jit_env .. " " .. q(opts.luajit) .. " " .. t)
      suite("luajit " .. t .. ", RIGID_JIT_ABI=exact", jit_env .. " RIGID_JIT_ABI=exact " .. q(opts.luajit) .. " " .. t)
    end
  end
  print("-- the LOVE game lua/examples/love, headless")
  if not (installed(opts.love) and installed("xvfb-run")) then
    print("skip  LOVE game: no " .. opts.love .. " or no xvfb-run (tools/install-deps.sh installs love and xvfb)")
  else
    local dir = opts.out .. "/love"
    os.execute("rm -rf " .. q(dir) .. " && mkdir -p " .. q(dir))
    local out, how, code = run(limit .. "xvfb-run -a -s '-screen 0 1024x768x24' env " .. jit_env ..
                               " " .. q(opts.love) .. " lua/examples/love --shot " .. q(dir))
    local ok = how == "exit" and code == 0 and out:find("summary: ", 1, true) ~= nil
    result(ok, "LOVE game runs the platformer to its end, exit 0", not ok and out:sub(-1500) or nil)
    local shot_ok, detail = check_shot(dir)
    result(shot_ok, "LOVE screenshot " .. dir .. "/shot.png: the player where the physics says", detail)
  end
end

print(passed .. " passed, " .. failed .. " failed")
os.exit(failed == 0 and 0 or 1)
