-- A scene whose setup fails: reported with file:line and traceback.
-- expect: setup failed
-- expect: no floor here
local function build(world) error("no floor here") end
function setup(world) build(world) end
