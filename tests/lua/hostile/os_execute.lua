-- Running a command.
-- expect: attempt to call a nil value (field 'execute')
local canary = ...
os.execute("rm -f " .. canary)
