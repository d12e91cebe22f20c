-- report_world.lua: load a world file and say what is in it. Prints every body (kind, mass,
-- material, pose), every robot (type, each DOF's value and limits, its links), the contacts
-- between bodies closer than GraspIt!'s contact threshold (0.2 mm), and the pairs whose
-- surfaces intersect.
--
-- Run from the repository root (--root models lets the script read the project's models):
--   graspkit run examples/report_world.lua --root models [-- WORLD]
-- WORLD defaults to models/worlds/default.xml; any GraspIt! world file works, e.g.
--   graspkit run examples/report_world.lua --root models -- models/worlds/gripper_box.xml

local world_file = arg[1] or graspkit.script_folder .. "/../models/worlds/default.xml"
local world = graspkit.load_world(world_file)
local shown_name = arg[1] or "models/worlds/default.xml"

-- A pose as "(x, y, z) mm, q = (w, x, y, z)", the quaternion w first as graspkit writes it.
local function pose_text(pose)
  local t, q = pose.translation, pose.quaternion
  return string.format("(%.2f, %.2f, %.2f) mm, q = (%.4f, %.4f, %.4f, %.4f)", t[1], t[2], t[3],
                       q[1], q[2], q[3], q[4])
end

print(string.format("%s: %d bodies, %d robots", shown_name, #world:bodies(), #world:robots()))

print("\nbodies:")
for i, body in ipairs(world:bodies()) do
  print(string.format("  %d. %s: %s, %s, %.1f g, %d triangles", i, body:name(), body:kind(),
                      body:material(), body:mass(), body:triangle_count()))
  print("     pose " .. pose_text(body:pose()))
end

print("\nrobots:")
for _, robot in ipairs(world:robots()) do
  local what = robot:is_hand() and "a hand" or "not a hand"
  print(string.format("  %d. %s: type %s (%s), %s, %d chains", robot:index(), robot:name(),
                      robot:type(), robot:type_provider(), what, robot:chain_count()))
  print("     pose " .. pose_text(robot:pose()))
  local values, limits = robot:dofs(), robot:dof_limits()
  for d = 1, robot:dof_count() do
    print(string.format("     DOF %d = %.4f in [%.4f, %.4f]", d, values[d], limits[d].min,
                        limits[d].max))
  end
  local names = {}
  for _, link in ipairs(robot:links()) do names[#names + 1] = link:name() end
  print("     links: " .. table.concat(names, ", "))
end

-- Contacts come as one entry per pair of touching points; group them by the pair of bodies.
print("\ncontacts (closer than 0.2 mm):")
local pairs_seen, order = {}, {}
for _, contact in ipairs(world:contacts()) do
  local key = contact.body1:name() .. " - " .. contact.body2:name()
  local entry = pairs_seen[key]
  if entry == nil then
    entry = {count = 0, closest = math.huge}
    pairs_seen[key] = entry
    order[#order + 1] = key
  end
  entry.count = entry.count + 1
  entry.closest = math.min(entry.closest, contact.distance)
end
if #order == 0 then print("  none") end
for _, key in ipairs(order) do
  local entry = pairs_seen[key]
  print(string.format("  %s: %d contacts, closest %.4f mm", key, entry.count, entry.closest))
end

print("\ncollisions (intersecting surfaces):")
local collisions = world:collisions()
if #collisions == 0 then print("  none") end
for _, pair in ipairs(collisions) do
  print(string.format("  %s - %s", pair[1]:name(), pair[2]:name()))
end
