-- main.lua: the platformer of lua/examples/platformer.lua as a LOVE game, on LuaJIT through
-- lua/rigid_jit.lua, drawn with love.graphics.  The scene script is the very file the
-- sandboxed host plays (`make run`); this file is its host: setup(world), then per fixed
-- step update(world, dt), one step, contact(world, event) for each event; finish(world).
--   RIGID_LIBRARY=build/librigid.so love lua/examples/love        play it (Escape quits)
--   ... love lua/examples/love --shot DIR [--shot-at SECONDS]
--       a run for the tests: one fixed step a frame (so the run is the same on any
--       machine), a screenshot after SECONDS of game time (default 2) written to
--       DIR/shot.pam and DIR/shot.png with DIR/shot.txt (where the physics puts the player
--       and how the world maps to pixels), finish(world) at the end, then exit (status 1
--       on any error).
local source = love.filesystem.getSource()
package.path = source .. "/../../?.lua;" .. package.path   -- lua/rigid_jit.lua of this tree
local rigid = require "rigid_jit"

local SCALE = 32                           -- pixels per metre
local COLORS = {                           -- by body name; the player's is nowhere else
  player = { 230, 40, 40 }, coin = { 250, 210, 30 }, flag = { 40, 170, 70 },
  crate = { 150, 100, 50 }, ledge = { 170, 120, 70 }, ground = { 90, 65, 50 },
  shuttle = { 60, 110, 200 },
}
local EDGE = { 235, 205, 150 }             -- the top of a one-way ledge: jump through from below
local DUST, DUST_TIME = { 235, 235, 225 }, 0.4   -- puffs where the scene's probe saw a landing
local SKY = { 140, 190, 240 }

local scene = setmetatable({}, { __index = _G })   -- the scene script's globals
local world, dt, total, steps, acc = nil, 0, 0, 0, 0
local player
local shot_dir, shot_at, shot_taken = nil, 2, false
local camera = { ox = 0, oy = 0 }          -- the pixel of world (0, 0); y grows upwards

local function color(c) return love.math.colorFromBytes(c[1], c[2], c[3]) end

local function load_scene(path)
  local f = assert(io.open(path, "rb"))
  local chunk = assert(loadstring(f:read("*a"), "@" .. path))
  f:close()
  setfenv(chunk, scene)
  chunk()
end

function love.load(args)
  local i = 1
  while args[i] do
    if args[i] == "--shot" then shot_dir, i = args[i + 1], i + 2
    elseif args[i] == "--shot-at" then shot_at, i = tonumber(args[i + 1]), i + 2
    else error("usage: love lua/examples/love [--shot DIR [--shot-at SECONDS]]") end
  end
  if shot_dir then
    -- a test has nobody to read an error screen
    love.errorhandler = function(msg)
      print(debug.traceback("love: " .. tostring(msg), 3))
      return function() return 1 end
    end
  end
  load_scene(source .. "/../platformer.lua")
  world = rigid.world()
  scene.setup(world)
  dt = world:fixed_step()
  total = math.ceil(scene.duration / dt - 1e-9)
  for _, b in ipairs(world:bodies()) do
    if b:name() == "player" then player = b end
  end
  assert(player, "the scene has a body named player")
  love.graphics.setBackgroundColor(color(SKY))
end

-- One fixed step, as the host takes it.
local function step()
  if scene.update then scene.update(world, dt) end
  world:advance(dt)
  if scene.contact then
    for _, e in ipairs(world:events()) do scene.contact(world, e) end
  end
  steps = steps + 1
  if steps == total then
    if scene.finish then scene.finish(world) end
    if shot_dir then love.event.quit(0) end
  end
end

function love.update(frame_time)
  if steps >= total then return end
  if shot_dir then return step() end
  acc = math.min(acc + frame_time, 0.25)
  while acc >= dt and steps < total do
    step()
    acc = acc - dt
  end
end

local function write(path, s)
  local f = assert(io.open(path, "wb"))
  f:write(s)
  f:close()
end

-- The picture as PAM (raw RGBA, which the test reads) and PNG, and what it shows.
local function take_shot(px, py, hw, hh)
  local record = ("x %.9g\ny %.9g\nhalf_width %.9g\nhalf_height %.9g\nscale %d\nox %.9g\n" ..
                  "oy %.9g\ncolor %d %d %d\nt %.9g\n")
                 :format(px, py, hw, hh, SCALE, camera.ox, camera.oy, COLORS.player[1],
                         COLORS.player[2], COLORS.player[3], steps * dt)
  love.graphics.captureScreenshot(function(image)
    local w, h = image:getDimensions()
    write(shot_dir .. "/shot.pam", ("P7\nWIDTH %d\nHEIGHT %d\nDEPTH 4\nMAXVAL 255\n" ..
                                    "TUPLTYPE RGB_ALPHA\nENDHDR\n"):format(w, h) .. image:getString())
    write(shot_dir .. "/shot.png", image:encode("png"):getString())
    write(shot_dir .. "/shot.txt", record)
    print(("love: screenshot at t = %.2f s in %s/shot.png"):format(steps * dt, shot_dir))
  end)
end

function love.draw()
  local W, H = love.graphics.getDimensions()
  local px, py = player:position()
  camera.ox = math.floor(W / 3 - px * SCALE + 0.5)
  camera.oy = H - 120
  local now = steps * dt
  for _, d in ipairs(scene.dust or {}) do   -- under the bodies, so the player stays in front
    local age = now - d.t
    if age >= 0 and age < DUST_TIME then
      local r, g, b = color(DUST)
      love.graphics.setColor(r, g, b, 1 - age / DUST_TIME)
      for k = -1, 1 do
        love.graphics.circle("fill", camera.ox + (d.x + k * (0.25 + age)) * SCALE,
                             camera.oy - d.y * SCALE - 4, (0.12 + 0.3 * age) * SCALE)
      end
    end
  end
  for _, b in ipairs(world:bodies()) do
    local x, y = b:position()
    local kind, a, c = b:shape()
    love.graphics.setColor(color(COLORS[b:name()] or { 0, 0, 0 }))
    local sx, sy = camera.ox + x * SCALE, camera.oy - y * SCALE
    if kind == "circle" then
      love.graphics.circle("fill", sx, sy, a * SCALE)
    elseif kind == "aabb" then
      love.graphics.rectangle("fill", sx - a * SCALE, sy - c * SCALE, 2 * a * SCALE, 2 * c * SCALE)
      local _, ny = b:one_way()
      if ny > 0 then
        love.graphics.setColor(color(EDGE))
        love.graphics.rectangle("fill", sx - a * SCALE, sy - c * SCALE, 2 * a * SCALE, 3)
      end
    end
  end
  love.graphics.setColor(1, 1, 1)
  love.graphics.print(("t = %.1f s   x = %.1f m   %s"):format(steps * dt, px,
                      player:grounded() and "grounded" or "in the air"), 10, 10)
  if shot_dir and not shot_taken and steps * dt >= shot_at then
    shot_taken = true
    local _, hw, hh = player:shape()
    take_shot(px, py, hw, hh)
  end
end

function love.keypressed(key)
  if key == "escape" then love.event.quit() end
end
