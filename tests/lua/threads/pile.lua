-- threads/pile.lua: a pile large enough that the step splits its stages (3000 circles and
-- boxes falling into a container), for the host's --threads: tests/lua/run.lua runs it with
-- --threads 1 and --threads 3 and compares the hash it prints at the end.
local W = 60
function setup(world)
  world:body{ type = "static", aabb = {W / 2 + 1, 0.5}, y = -0.5 }
  world:body{ type = "static", aabb = {0.5, 40}, x = -W / 2 - 0.5, y = 40 }
  world:body{ type = "static", aabb = {0.5, 40}, x = W / 2 + 0.5, y = 40 }
  for i = 0, 2999 do
    local x, y = -W / 2 + 0.5 + (i % W) + 0.01 * (i % 7), 0.5 + (i // W) * 1.05
    if i % 3 == 0 then
      world:body{ aabb = {0.45, 0.4}, x = x, y = y, vx = (i % 5) - 2 }
    else
      world:body{ circle = 0.45, x = x, y = y, vx = (i % 5) - 2, restitution = (i % 4 == 1) and 0.3 or 0 }
    end
  end
end

function update(world, dt) end

function finish(world)
  print(("pile: %d bodies, hash %016x"):format(world:body_count(), world:hash()))
end

duration = 1
