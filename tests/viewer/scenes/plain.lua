-- plain.lua: no scene functions; the script makes and steps a world itself, 30 steps.
local rigid = require "rigid"
local w = rigid.world{ gravity = { 0, -9.81 } }
local b = w:body{ y = 2, circle = 0.5, name = "ball" }
w:body{ type = "static", y = -0.5, aabb = { 3, 0.5 }, name = "floor" }
for i = 1, 30 do w:step(1 / 60) end
local _, y = b:position()
print(string.format("after 30 steps: y = %.3f", y))
