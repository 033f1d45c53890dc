-- Exiting the host with success from inside the script.
-- expect: attempt to call a nil value (field 'exit')
os.exit(0)
