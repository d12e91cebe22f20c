-- plan_mug.lua: plan grasps of a mug with the simulated-annealing planner, then close the hand
-- on each of the best and measure it. Loads the default world (the bh8 hand above a mug), runs
-- GraspIt!'s contact energy for a small budget with a fixed seed (so every run prints the same
-- list), and prints each grasp: its energy, its quality once closed (epsilon, volume, contacts,
-- force closure) and where the palm is.
--
-- Run from the repository root (--root models lets the script read the project's models):
--   graspkit run examples/plan_mug.lua --root models [-- WORLD [STEPS]]
-- WORLD is any world file with a hand and a graspable body (default models/worlds/default.xml);
-- STEPS the planner's budget (default 3000).

local world_file = arg[1] or graspkit.script_folder .. "/../models/worlds/default.xml"
local steps = tonumber(arg[2] or "3000")
local world = graspkit.load_world(world_file)

local planner = graspkit.planner("simann", {
  world = world,
  energy = "contact",  -- or a Lua function, see docs/lua.md
  seed = 1,
  top = 5,
})
local done, seconds = planner:run{steps = steps}
print(string.format("%d steps in %.2f s", done, seconds))

local grasps = planner:finish()  -- closes the hand on each grasp and measures it
local closures = 0
print(string.format("%4s %10s %9s %9s %8s %3s  %s", "rank", "energy", "epsilon", "volume",
                    "contacts", "fc", "palm (mm)"))
for rank, g in ipairs(grasps) do
  local t = g.pose.translation
  print(string.format("%4d %10.4f %9.4f %9.4f %8d %3s  %.1f %.1f %.1f", rank, g.energy,
                      g.epsilon, g.volume, g.contacts, g.force_closure and "yes" or "no", t[1],
                      t[2], t[3]))
  if g.force_closure then closures = closures + 1 end
end
print(string.format("%d grasps, %d force closure", #grasps, closures))
