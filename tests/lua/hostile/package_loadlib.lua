-- Loading a C library.
-- expect: attempt to index a nil value (global 'package')
local open = package.loadlib("libc.so.6", "system")
open("true")
