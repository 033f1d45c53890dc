-- require of anything but rigid.
-- expect: module 'io' is not available in the sandbox
local io = require "io"
io.write("hi")
