-- conf.lua: the window of the LOVE platformer (main.lua).
function love.conf(t)
  t.identity = "rigid-platformer"
  t.version = "11.4"
  t.window.title = "rigid: platformer (LuaJIT FFI binding)"
  t.window.width, t.window.height = 800, 450
  t.modules.audio, t.modules.sound, t.modules.joystick = false, false, false
end
