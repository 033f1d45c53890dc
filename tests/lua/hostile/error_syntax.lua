-- A script that does not parse: reported with file:line, before anything runs.
-- expect: loading failed
-- expect: unexpected symbol near '='
-- traceback: no
local x = = 1
