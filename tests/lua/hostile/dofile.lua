-- dofile and loadfile are gone.
-- expect: attempt to call a nil value (global 'dofile')
local canary = ...
dofile(canary)
