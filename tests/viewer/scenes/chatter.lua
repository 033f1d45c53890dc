-- chatter.lua: a script that prints far more than the replay's log keeps (8 MiB): the page
-- says how many lines it dropped, and the run is unharmed.
duration = 0.5
local line = string.rep("x", 999)
function update(world, dt)
  for i = 1, 400 do print(line) end
end
