-- rollback.lua: rollback netcode (GGPO style) with world:save() and world:restore().
--
-- Two players push boxes into the pit in the middle of an arena, each its own from its
-- end; a box in the pit scores for its player and drops in again at that player's end.
-- Each player's machine (a "peer") runs its own world.  A player's input reaches the other
-- peer 3 to 7 frames late, so a peer never waits for it: it PREDICTS the other's input
-- (the last one it knows, repeated) and simulates on.  Each frame it keeps a snapshot of
-- the state it starts from.  When a late input shows that a prediction was wrong, the peer
-- ROLLS BACK (restores the snapshot of that frame) and RESIMULATES every frame since with
-- what it now knows, in one go, before the next frame.  Physics is bit-identical, so once
-- every input has arrived both peers hold exactly the state of a reference run that had
-- every input on time: finish() compares the three worlds' world:hash() and the scores,
-- and prints how much was rolled back.
--
-- The host steps the reference run (the world passed to setup/update/contact, which the
-- picture shows); the peers are two more worlds this script steps itself.
--   build/rigid lua/examples/rollback.lua --svg build/rollback.svg
duration = 20
caption = "the reference run; both peers, fed inputs 3-7 frames late, end on its hash"

local WHISTLE = 19 * 60              -- the frame the match ends (the last second, all stop)
local RUN, PUSH, JUMP = 4, 30, 7.5   -- m/s target speed, kg/s speed gain, N s jump impulse
local ARENA = 8                      -- m, half width
local DT                             -- s, the fixed step (setup reads it from the host's world)

-- ---------------------------------------------------------------- the game
--
-- Everything here is the same in every world.  The state a game needs besides physics
-- (the score) lives in `game` and is saved and restored with the world.

-- Player p's boxes come from its end of the arena.
local function spawn_box(world, p, x, y)
  return world:body{ aabb = {0.4, 0.4}, x = x, y = y, mass = 1.5, friction = 0.5,
                     name = "box " .. p }
end

-- A world with the arena, the pit in its middle, the two players and a box each; returns
-- the game around it.
local function build(world)
  world:set_gravity(0, -20)
  world:body{ type = "static", aabb = {ARENA + 1, 0.5}, y = -0.5, name = "floor" }
  world:body{ type = "static", aabb = {0.5, 1.5}, x = -ARENA - 0.5, y = 1.5 }
  world:body{ type = "static", aabb = {0.5, 1.5}, x = ARENA + 0.5, y = 1.5 }
  world:body{ type = "static", sensor = true, aabb = {0.5, 0.4}, y = 0.4, name = "pit" }
  local players = {
    world:body{ aabb = {0.3, 0.5}, x = -7.5, y = 0.5, friction = 0.1, name = "player 1" },
    world:body{ aabb = {0.3, 0.5}, x = 7.5, y = 0.5, friction = 0.1, name = "player 2" },
  }
  spawn_box(world, 1, -4, 0.4)
  spawn_box(world, 2, 4, 0.4)
  return { world = world, players = players, score = { 0, 0 } }
end

-- An input is one of "idle", "left", "right", "jump", "left+jump", "right+jump".
local function apply_inputs(game, inputs)
  for p, body in ipairs(game.players) do
    local input = inputs[p]
    local move = input:find("left") and -1 or input:find("right") and 1 or 0
    local vx = body:velocity()
    local gain = body:grounded() and PUSH or PUSH / 4   -- less control in the air
    body:apply_force((RUN * move - vx) * gain, 0)
    if input:find("jump") and body:grounded() then body:apply_impulse(0, JUMP) end
  end
end

-- After a step: a box that reached the pit scores for its player and drops in again at
-- that player's end.
local function on_contact(game, e)
  if e.kind ~= "begin" then return end
  local pit, box = e.a, e.b
  if pit:name() ~= "pit" then pit, box = box, pit end
  local p = pit:name() == "pit" and tonumber((box:name() or ""):match("^box (%d)$"))
  if p and box:destroy() then
    game.score[p] = game.score[p] + 1
    spawn_box(game.world, p, p == 1 and -5 or 5, 3)
  end
end

-- One whole frame, as a peer runs it.
local function simulate(game, inputs)
  apply_inputs(game, inputs)
  game.world:advance(DT)
  for _, e in ipairs(game.world:events()) do on_contact(game, e) end
end

-- ---------------------------------------------------------------- the players
--
-- A player looks at its own peer's world (which may still hold a wrong guess of the other
-- player) and presses: it gets behind its box and pushes it into the pit, hopping over the
-- box when it is on the wrong side; now and then it dawdles.  What it pressed is history:
-- INPUT[p][f] is player p's input at frame f, resimulations reuse it, and the reference
-- run is given it on time.  A player's mind (its dawdling, its dice) is no part of the
-- game's state and is never rolled back.

local function random(seed)
  return function()
    seed = (seed * 1103515245 + 12345) % 2147483648
    return seed / 2147483648
  end
end

local INPUT = { {}, {} }

local function decide(peer, frame)
  local game, p = peer.game, peer.me
  if frame > WHISTLE then return "idle" end       -- the match is over: everyone stops
  local out = p == 1 and -1 or 1                  -- toward the player's end
  local inward, outward = p == 1 and "right" or "left", p == 1 and "left" or "right"
  if peer.dawdle > 0 then
    peer.dawdle = peer.dawdle - 1
    return peer.dawdling
  end
  if peer.dice() < 0.01 then
    peer.dawdle = 10 + math.floor(peer.dice() * 40)
    peer.dawdling = peer.dice() < 0.5 and "idle" or "jump"
  end
  local x, y = game.players[p]:position()
  local box
  for _, b in ipairs(game.world:bodies()) do
    if b:name() == "box " .. p then box = b:position() end
  end
  if box == nil then return "idle" end
  local on_box = y > 1                                  -- it stands 0.8 m tall
  if not on_box and out * (x - box) > 0.5 then return inward end   -- behind it: push
  if not on_box and math.abs(x - box) < 1.2 then return outward .. "+jump" end  -- hop over
  return outward                                        -- walk out, off it, to get behind
end

-- ---------------------------------------------------------------- the network
--
-- A packet carries one player's input of one frame and arrives 3 to 7 frames after it was
-- sent, in order (a GGPO-style stream repeats the inputs not yet acknowledged, so a lost
-- packet only adds delay).

local in_flight = { {}, {} }        -- in_flight[p]: packets on their way to peer p
local last_arrival = { 0, 0 }
local delay = random(4242)

local function send(to, frame, input)
  local arrives = math.max(last_arrival[to], frame + 3 + math.floor(delay() * 5))
  last_arrival[to] = arrives
  table.insert(in_flight[to], { frame = frame, input = input, arrives = arrives })
end

-- The packets for peer p that have arrived by frame `now` (all of them when now is nil).
local function arrived(p, now)
  local out, queue = {}, in_flight[p]
  while queue[1] and (now == nil or queue[1].arrives <= now) do
    out[#out + 1] = table.remove(queue, 1)
  end
  return out
end

-- ---------------------------------------------------------------- a peer

local function new_peer(me)
  return {
    me = me, other = 3 - me,
    game = build(rigid.world()),
    frame = 0,       -- frames simulated
    known = {},      -- known[f]: the other player's input of frame f, once it arrived
    last_known = 0,  -- the last frame known (every frame before it is known too)
    used = {},       -- used[f]: the other's input frame f was simulated with
    saved = {},      -- saved[f]: the state at the start of frame f, kept until f is known
    rollbacks = 0, resimulated = 0, deepest = 0,
    dice = random(me * 7919), dawdle = 0, dawdling = "idle",   -- the player's mind
  }
end

-- The other player's input at frame f: known, or else the last one known, repeated.
local function predict(peer, f)
  return peer.known[f] or peer.known[peer.last_known] or "idle"
end

-- A game's whole state: the world's snapshot and the score.  The body values the game
-- holds (game.players) stay valid across restores: a body that existed at the save is the
-- same Lua value afterwards.  Boxes spawned after it are destroyed by the restore, and the
-- resimulation spawns them again.
local function save(game)
  return { world = game.world:save(), score = { game.score[1], game.score[2] } }
end

local function restore(game, state)
  game.world:restore(state.world)
  game.score = { state.score[1], state.score[2] }
end

local function run_frame(peer, f)
  peer.saved[f] = save(peer.game)
  local inputs = { [peer.me] = INPUT[peer.me][f], [peer.other] = predict(peer, f) }
  peer.used[f] = inputs[peer.other]
  simulate(peer.game, inputs)
  peer.frame = f
end

-- Late inputs arrive: when one shows a frame was simulated with a wrong guess, go back to
-- that frame and simulate it and every frame since again.
local function receive(peer, packets)
  if #packets == 0 then return end
  local first = packets[1].frame
  for _, packet in ipairs(packets) do
    peer.known[packet.frame] = packet.input
    peer.last_known = packet.frame
  end
  -- A new known input also changes the guesses for the frames after it.
  for f = first, peer.frame do
    if peer.used[f] ~= predict(peer, f) then
      local now = peer.frame
      restore(peer.game, peer.saved[f])
      for g = f, now do run_frame(peer, g) end
      peer.rollbacks = peer.rollbacks + 1
      peer.resimulated = peer.resimulated + (now - f + 1)
      peer.deepest = math.max(peer.deepest, now - f + 1)
      break
    end
  end
  -- Frames whose inputs are all known can never be rolled back to again.
  for f = first, peer.last_known do peer.saved[f], peer.used[f] = nil, nil end
end

local peers = { new_peer(1), new_peer(2) }

-- ---------------------------------------------------------------- the host's callbacks

local reference, frame = nil, 0

function setup(world)
  reference = build(world)
  DT = world:fixed_step()            -- the step as rg_real holds it, the same in every world
  for _, peer in ipairs(peers) do peer.game.world:set_fixed_step(DT) end
end

-- Before each of the host's steps: frame `frame` on the peers, and its inputs, on time, in
-- the reference, which the host then steps.
function update(world, dt)
  frame = frame + 1
  for _, peer in ipairs(peers) do
    receive(peer, arrived(peer.me, frame))
    INPUT[peer.me][frame] = decide(peer, frame)
    send(peer.other, frame, INPUT[peer.me][frame])
    run_frame(peer, frame)
  end
  apply_inputs(reference, { INPUT[1][frame], INPUT[2][frame] })
end

function contact(world, e)
  on_contact(reference, e)
end

function finish(world)
  -- The match is over; the last packets arrive and the peers catch up.
  for _, peer in ipairs(peers) do receive(peer, arrived(peer.me)) end
  local want = world:hash()
  print(("reference: %d frames, score %d : %d, hash %016x"):format(frame, reference.score[1],
                                                                  reference.score[2], want))
  for _, peer in ipairs(peers) do
    local got = peer.game.world:hash()
    print(("peer %d: %d rollbacks, %d frames resimulated (deepest %d), score %d : %d, hash %016x")
          :format(peer.me, peer.rollbacks, peer.resimulated, peer.deepest, peer.game.score[1],
                  peer.game.score[2], got))
    assert(peer.frame == frame, "the peer ran every frame")
    assert(got == want, ("peer %d ends on another hash than the reference"):format(peer.me))
    assert(peer.game.score[1] == reference.score[1] and peer.game.score[2] == reference.score[2],
           "the peer's score")
    assert(peer.rollbacks > 0, "late inputs made the peer roll back")
  end
  assert(reference.score[1] > 0 and reference.score[2] > 0, "both players scored")
end
