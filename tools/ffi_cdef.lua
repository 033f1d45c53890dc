-- ffi_cdef.lua: the declarations of include/rigid.h as LuaJIT's ffi.cdef takes them, made
-- by the C preprocessor from the header itself, one declaration a line.
--   lua5.4 tools/ffi_cdef.lua                         prints them
--   lua5.4 tools/ffi_cdef.lua --check lua/rigid_jit.lua   fails (with a diff) when the block
--                                                     in the binding differs
--   lua5.4 tools/ffi_cdef.lua --update lua/rigid_jit.lua  rewrites that block
-- The block sits between the lines `local RIGID_H = [[` and `]]`.  rg_real is left out: the
-- binding declares it float or double by the size of the library it loads.  The system
-- headers (stddef.h, stdint.h) are replaced by empty ones: LuaJIT knows their types.
-- Integer constants the header keeps as macros (the preprocessor drops them) follow as
-- static const declarations, which ffi.cdef takes.
-- Environment: CC (default cc).
local mode, file = arg[1], arg[2]
local HEADER = "include/rigid.h"
local OPEN, CLOSE = "local RIGID_H = [[", "]]"

local function sh(cmd)
  local p = assert(io.popen(cmd))
  local out = p:read("a")
  local ok, how, code = p:close()
  if not ok then error(cmd .. ": " .. tostring(how) .. " " .. tostring(code), 0) end
  return out
end

local function declarations()
  local stub = os.tmpname()
  os.remove(stub)
  sh("mkdir -p '" .. stub .. "' && : > '" .. stub .. "/stddef.h' && : > '" .. stub .. "/stdint.h'")
  local ok, text = pcall(sh, (os.getenv("CC") or "cc") .. " -E -P -nostdinc -I'" .. stub .. "' " .. HEADER)
  sh("rm -rf '" .. stub .. "'")
  if not ok then error(text, 0) end
  text = text:gsub("__attribute__%s*%(%(visibility%(\"default\"%)%)%)", "")
             :gsub("typedef%s+float%s+rg_real%s*;", "")
             :gsub("%s+", " ")
  local lines = {}
  for decl in text:gmatch("[^;]+;") do
    decl = decl:gsub("^ ", ""):gsub(" ;$", ";"):gsub("%( ", "("):gsub(" %)", ")")
    -- a struct or enum body: one member a line
    decl = decl:gsub("{ ", "{\n  "):gsub(" }", "\n}")
    if decl:find("^enum") then decl = decl:gsub(", ", ",\n  ") end
    lines[#lines + 1] = decl
  end
  -- members of a struct come out as declarations of their own; join them back up
  local out, open = {}, false
  for _, l in ipairs(lines) do
    if open then
      out[#out] = out[#out] .. (l:find("^}") and "\n" or "\n  ") .. l
    else
      out[#out + 1] = l
    end
    local opens = select(2, out[#out]:gsub("{", "")) - select(2, out[#out]:gsub("}", ""))
    open = opens > 0
  end
  -- #define RG_NAME <integer literal>[u]: as static const uint32_t or int32_t
  local f = assert(io.open(HEADER, "rb"))
  for line in f:read("a"):gmatch("[^\n]+") do
    local name, value = line:match("^#define%s+(RG_[%w_]+)%s+(%S+)")
    local digits, u = (value or ""):match("^(%-?%d+)(u?)$")
    if not digits then digits, u = (value or ""):match("^(0[xX]%x+)(u?)$") end
    if digits then
      out[#out + 1] = ("static const %s %s = %s%s;"):format(u == "u" and "uint32_t" or "int32_t",
                                                          name, digits, u)
    end
  end
  f:close()
  return table.concat(out, "\n") .. "\n"
end

local function read(path)
  local f = assert(io.open(path, "rb"))
  local s = f:read("a")
  f:close()
  return s
end

-- The binding's text split around the block: before, block, after.
local function split(src, path)
  local a = src:find("\n" .. OPEN .. "\n", 1, true)
  if not a then error(path .. ": no line `" .. OPEN .. "`", 0) end
  local start = a + #OPEN + 2
  local b = src:find("\n" .. CLOSE .. "\n", start - 1, true)
  if not b then error(path .. ": no line `" .. CLOSE .. "` after `" .. OPEN .. "`", 0) end
  return src:sub(1, start - 1), src:sub(start, b), src:sub(b + 1)
end

local decls = declarations()
if mode == nil then
  io.write(decls)
elseif mode == "--check" and file then
  local _, block = split(read(file), file)
  if block == decls then
    print("ffi_cdef: the ffi.cdef of " .. file .. " matches " .. HEADER)
  else
    local want, have = os.tmpname(), os.tmpname()
    local f = assert(io.open(want, "wb")); f:write(decls); f:close()
    f = assert(io.open(have, "wb")); f:write(block); f:close()
    io.write(sh("diff -u '" .. have .. "' '" .. want .. "' || true"))
    os.remove(want); os.remove(have)
    print("ffi_cdef: the ffi.cdef of " .. file .. " differs from " .. HEADER ..
          " (above: - in the binding, + from the header); `make ffi-cdef` rewrites it")
    os.exit(1)
  end
elseif mode == "--update" and file then
  local before, _, after = split(read(file), file)
  local f = assert(io.open(file, "wb"))
  f:write(before, decls, after)
  f:close()
  print("ffi_cdef: wrote the ffi.cdef of " .. file .. " from " .. HEADER)
else
  io.stderr:write("usage: lua5.4 tools/ffi_cdef.lua [--check FILE | --update FILE]\n")
  os.exit(2)
end
