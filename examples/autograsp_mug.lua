-- autograsp_mug.lua: close a hand on an object and measure the grasp. Loads the default world
-- (the bh8 hand above a mug standing on a floor), closes the hand with GraspIt!'s autograsp
-- (every finger moves at its DOF's default velocity until it touches something or reaches its
-- limit), then prints each contact and the grasp's quality: epsilon (the radius of the largest
-- ball around the origin inside the grasp wrench space; > 0 exactly when the grasp is force
-- closure), the wrench space's volume, and whether the grasp is force closure.
--
-- Run from the repository root (--root models lets the script read the project's models):
--   graspkit run examples/autograsp_mug.lua --root models [-- WORLD [OBJECT]]
-- WORLD is any world file with a hand (default models/worlds/default.xml); OBJECT the name of
-- the body to grasp (default the first graspable body).

local world_file = arg[1] or graspkit.script_folder .. "/../models/worlds/default.xml"
local world = graspkit.load_world(world_file)

local hand = nil
for _, robot in ipairs(world:robots()) do
  if hand == nil and robot:is_hand() then hand = robot end
end
if hand == nil then error(world_file .. " has no hand") end

local object = nil
if arg[2] then
  object = world:body(arg[2])
else
  for _, body in ipairs(world:bodies()) do
    if object == nil and body:kind() == "graspable" then object = body end
  end
end
if object == nil then error(world_file .. " has no graspable body") end

local function numbers(list, format)
  local parts = {}
  for i, value in ipairs(list) do parts[i] = string.format(format, value) end
  return table.concat(parts, " ")
end

print(string.format("world: %s", tostring(world)))
print(string.format("hand: %s (%s, %d DOFs), object: %s", hand:name(), hand:type(),
                    hand:dof_count(), object:name()))
print("DOFs before: " .. numbers(hand:dofs(), "%.4f"))

local motion = hand:autograsp()
print(string.format("autograsp: %s after %d steps", motion.ended, motion.steps))
print("DOFs after:  " .. numbers(hand:dofs(), "%.4f"))

local grasp = hand:grasp(object)
print(string.format("contacts: %d", grasp:contact_count()))
for _, contact in ipairs(grasp:contacts()) do
  -- point1 lies on body1 (the hand's link), point2 on body2 (the object); both in mm, world frame.
  print(string.format("  %-18s at (%s)  gap %.3f mm  mu %.2f", contact.body1:name(),
                      numbers(contact.point1, "%.1f"), contact.distance, contact.mu))
end
if grasp:failure() then print("no wrench space: " .. grasp:failure()) end
print(string.format("epsilon: %.6f", grasp:epsilon()))
print(string.format("volume: %.6f", grasp:volume()))
print(string.format("force closure: %s", grasp:force_closure() and "yes" or "no"))
