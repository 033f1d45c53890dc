-- Making bytecode: string.dump is gone.
-- expect: attempt to call a nil value (field 'dump')
local f = load(string.dump(function() return 1 end))
print(f())
