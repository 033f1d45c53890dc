-- table.move over 2^63 empty slots: C work the sandbox charges.
-- expect: instruction budget exhausted
-- args: 
table.move({}, 1, math.maxinteger - 1, 2)
