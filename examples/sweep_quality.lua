-- sweep_quality.lua: how grasp quality changes with the direction a hand comes from. The bh8
-- hand is placed at evenly spaced angles around the mug (handle at 0 degrees), facing it, and
-- at each angle opens, moves in until it touches, closes, and has its grasp measured; the
-- results are printed as a table. The pose algebra and the grasp steps are in grasp_sweep.lua
-- beside this file.
--
-- Run from the repository root (--root models lets the script read the project's models):
--   graspkit run examples/sweep_quality.lua --root models [-- ANGLES [WORLD]]
-- ANGLES is the number of angles (default 12, every 30 degrees); WORLD a world file with a hand
-- and a body named "mug" (default models/worlds/default.xml).

local sweep = require("grasp_sweep")

local count = math.tointeger(tonumber(arg[1] or "12"))
if count == nil or count < 1 then error("ANGLES must be a whole number >= 1, got " .. arg[1]) end
local world_file = arg[2] or graspkit.script_folder .. "/../models/worlds/default.xml"

local world = graspkit.load_world(world_file)
print(string.format("%s: %s approaching the mug from %d directions",
                    arg[2] or "models/worlds/default.xml", world:robot(1):name(), count))

local records = sweep.run(world, {count = count})
sweep.print_table(records)

local best = sweep.best(records)
local closures = 0
for _, r in ipairs(records) do
  if r.force_closure then closures = closures + 1 end
end
print(string.format("force closure at %d of %d angles; best epsilon %.4f at %.1f degrees", closures,
                    #records, best.epsilon, math.deg(best.angle)))
