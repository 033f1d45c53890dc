-- sliding_box.lua: crates shoved across floors of different grip, seen from above (no
-- gravity in the picture: surface friction F = mu * N against the motion, the floor being
-- the whole plane under each crate).  Each stops at v0^2 / (2 mu g), less half a step of
-- travel, and never creeps backwards.
--   build/rigid lua/examples/sliding_box.lua --svg build/sliding_box.svg
duration = 3
caption = "seen from above: friction mu N from the floor under each crate; a ring marks v0^2/(2 mu g)"

local V0, G, DT = 8, 9.81, 1 / 60
local crates = {}

function setup(world)
  world:set_fixed_step(DT)
  for i, mu in ipairs{ 0.3, 0.6, 1.2 } do
    local lane = (i - 1) * -1.5
    local c = world:body{ mass = 20, y = lane, vx = V0, name = string.format("mu %.1f", mu),
                          surface_friction = { mu, 20 * G },
                          aabb = { 0.4, 0.4 } }
    crates[i] = { body = c, mu = mu, min_vx = V0 }
    -- Where the continuous law says it stops: v0^2 / (2 mu g), a marker without a shape.
    world:body{ type = "static", x = V0 * V0 / (2 * mu * G), y = lane, name = "v0^2/(2 mu g)" }
  end
end

local t = 0
function update(world, dt)
  t = t + dt
  for _, c in ipairs(crates) do
    local vx = c.body:velocity()
    c.min_vx = math.min(c.min_vx, vx)
    if vx == 0 and not c.stopped then c.stopped = t end
  end
end

function finish(world)
  for _, c in ipairs(crates) do
    local a = c.mu * G
    local n = math.floor(V0 / (a * DT))
    local exact = DT * (n * V0 - a * DT * n * (n + 1) / 2)   -- the discrete stop
    local x = c.body:position()
    print(string.format("%s: stopped after %.2f s at x = %.3f m (v0^2/(2 mu g) = %.3f m, discrete %.3f m)",
      c.body:name(), c.stopped or -1, x, V0 * V0 / (2 * a), exact))
    assert(c.stopped, "came to rest")
    assert(math.abs(x - exact) < 1e-3 * exact, "stopping distance")
    assert(c.min_vx >= 0, "friction never reverses the crate")
  end
end
