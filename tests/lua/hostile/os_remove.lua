-- Removing a file: os has only clock and time.
-- expect: attempt to call a nil value (field 'remove')
local canary = ...
os.remove(canary)
