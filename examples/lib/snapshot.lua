-- A picture of a deck's trajectory: its last frame as a PNG, drawn by the repository's
-- Python package (python3 -m slender render, Debian's python3 with matplotlib and h5py).
-- A machine without them, or a deck copied out of the repository, skips the picture with a
-- note; the run is not affected. -v plots=0 switches pictures off.
--   local snapshot = dofile(<this file>)
--   snapshot.render("classic.h5", "classic.png", { radius = 30, field = "bend.plastic_curvature" })
local slender = require("slender")
local M = {}
local here = debug.getinfo(1, "S").source:match("^@(.*)/[^/]*$") or "."
local python_dir = here .. "/../../python"

function M.render(h5, png, opts)
  opts = opts or {}
  if slender.var("plots", 1) == 0 then return false end
  local fh = io.open(python_dir .. "/slender/plot.py", "r")
  if not fh then
    print("picture skipped (no " .. python_dir .. "; draw it later with python3 -m slender render): " .. png)
    return false
  end
  fh:close()
  local cmd = "HDF5_USE_FILE_LOCKING=FALSE PYTHONPATH='" .. python_dir .. "' /usr/bin/python3 -m slender render '" ..
              h5 .. "' '" .. png .. "'"
  if opts.radius then cmd = cmd .. " --radius " .. opts.radius end
  if opts.field then cmd = cmd .. " --field '" .. opts.field .. "'" end
  -- the deck still holds its trajectory open: read it without HDF5's file lock
  local ok = os.execute(cmd .. " > /dev/null 2>&1")
  print((ok and "picture: " or "picture skipped (needs /usr/bin/python3 with matplotlib and h5py): ") .. png)
  return ok
end

return M
