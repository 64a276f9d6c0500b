-- Test deck of the Python package: a Lua loop that never returns and never steps a
-- simulation, so it cannot act on SIGTERM: a timeout has to kill it.
while true do end
