-- A scene whose update never returns: each call into the script has its own budget.
-- expect: update failed
-- expect: instruction budget exhausted
-- args: --budget 1000000 --steps 10
local calls = 0
function setup(world) world:body{ name = "bystander" } end
function update(world, dt)
  calls = calls + 1
  if calls == 3 then while true do end end
end
