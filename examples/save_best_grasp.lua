-- save_best_grasp.lua: search for a good grasp and keep it. Runs the sweep of sweep_quality.lua
-- (the bh8 hand closing on the mug from evenly spaced directions, code in grasp_sweep.lua),
-- saves the world of the grasp with the largest epsilon as a GraspIt! world file, then loads
-- that file again and checks that the hand's pose, its DOF values and the grasp's quality came
-- back the same (an error, exit status 1, when they did not).
--
-- Run from the repository root; the script may only write below a folder given with
-- --allow-write:
--   mkdir -p out
--   graspkit run examples/save_best_grasp.lua --root models --allow-write out \
--       -- out/best.xml [ANGLES]
-- ANGLES is the number of directions tried (default 12).

local sweep = require("grasp_sweep")

local output = arg[1]
if output == nil then
  error("usage: graspkit run save_best_grasp.lua --allow-write DIR -- DIR/FILE.xml [ANGLES]")
end
local count = math.tointeger(tonumber(arg[2] or "12"))
if count == nil or count < 1 then error("ANGLES must be a whole number >= 1, got " .. arg[2]) end

local world = graspkit.load_world(graspkit.script_folder .. "/../models/worlds/default.xml")
local records = sweep.run(world, {count = count})
sweep.print_table(records)

local best = sweep.best(records)
if not best.force_closure then
  print("warning: no direction gave force closure; saving the best there is")
end

-- The record keeps the world its grasp was made in: the hand is still closed on the mug.
best.world:save(output)
local hand = best.world:robot(1)
print(string.format("saved %s: %s at %.1f degrees, %d contacts, epsilon %.4f, volume %.4f",
                    best.world:file(), hand:name(), math.deg(best.angle), best.contacts,
                    best.epsilon, best.volume))
print("  hand pose " .. tostring(hand:pose()))
print("  DOFs " .. table.concat(hand:dofs(), " "))

-- Load the file back: the file format keeps poses and DOF values, and the contacts (and so the
-- quality) follow from them.
local reloaded = graspkit.load_world(output)
local again = reloaded:robot(1)
local moved, turned = graspkit.pose_distance(hand:pose(), again:pose())
if moved > 1e-6 or turned > 1e-9 then
  error(string.format("the hand pose did not round-trip: %g mm, %g rad apart", moved, turned))
end
for i, value in ipairs(hand:dofs()) do
  local back = again:dofs()[i]
  if math.abs(back - value) > 1e-9 then
    error(string.format("DOF %d did not round-trip: saved %.17g, loaded %.17g", i, value, back))
  end
end
local grasp = again:grasp("mug")
if grasp:contact_count() ~= best.contacts or math.abs(grasp:epsilon() - best.epsilon) > 1e-9 then
  error(string.format("the reloaded grasp differs: %d contacts, epsilon %.6f",
                      grasp:contact_count(), grasp:epsilon()))
end
print(string.format("reloaded %s: pose within %.2g mm and %.2g rad, same DOFs, %d contacts, " ..
                    "epsilon %.4f", output, moved, turned, grasp:contact_count(), grasp:epsilon()))
