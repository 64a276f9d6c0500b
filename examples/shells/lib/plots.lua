-- Plots of the shell decks: runs scripts/shell_plots.py with Debian's python3 (matplotlib,
-- h5py). A machine without them skips the plots with a note; the run is not affected.
-- -v plots=0 switches them off.
local slender = require("slender")
local M = {}
local here = debug.getinfo(1, "S").source:match("^@(.*)/[^/]*$") or "."
local script = here .. "/../../../scripts/shell_plots.py"

-- plots.run("econe", "out/econe.csv", "out/econe.png"): the last argument is the PNG
function M.run(...)
  local args = { ... }
  if slender.var("plots", 1) == 0 then return false end
  local fh = io.open(script, "r")
  if not fh then
    -- a deck copied out of the repository: say where the script was looked for
    print("plot skipped (no " .. script .. "; plot later with scripts/shell_plots.py): " .. args[#args])
    return false
  end
  fh:close()
  local quoted = {}
  for i, a in ipairs(args) do quoted[i] = "'" .. a .. "'" end
  -- the deck still holds its dumps open: read them without HDF5's file lock
  local ok = os.execute("HDF5_USE_FILE_LOCKING=FALSE /usr/bin/python3 '" .. script .. "' " .. table.concat(quoted, " ") ..
                        " > /dev/null 2>&1")
  if ok then
    print("plot: " .. args[#args])
  else
    print("plot skipped (needs /usr/bin/python3 with matplotlib and h5py): " .. args[#args])
  end
  return ok
end

return M
