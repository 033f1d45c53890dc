-- world:restore(s) reads all of s in C (the checksum of its body list here) before it can
-- refuse it: restores of a 4 MiB string are charged a unit a byte, so the budget stops this
-- loop at its fifth with the time limit off (uncharged, each was 4 ms of C for a few units).
-- The pieces of s are collected first: while two long strings live, every instruction is
-- charged what comparing them may cost (lua/llong.c), which would stop the loop anyway.
-- expect: instruction budget exhausted
-- expect: restore_long.lua:17:
-- args: --budget 20000000 --timeout 0
local rigid = require "rigid"
local w = rigid.world{}
local n = 4 << 20
local function u32(v) return string.char(v & 255, (v >> 8) & 255, (v >> 16) & 255, v >> 24) end
-- the header of a snapshot string, a body list of n zero bytes, a wrong checksum after it
local s = "rgluasn1" .. u32(n) .. string.rep("\0", n + 8)
collectgarbage()
local refused = 0
for _ = 1, 300 do refused = refused + (pcall(w.restore, w, s) and 0 or 1) end
print("300 restores, " .. refused .. " refused")
