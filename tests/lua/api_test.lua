-- The Lua API a GraspIt! user reaches for (graspit_interface's services), on the project's own
-- models (run with --root models): body geometry queries, look_at, eigengrasps, virtual
-- contacts, collision switches, removing bodies, DOF motions, approach directions, search
-- energies. Truths come from the model files (box.xml is 60 x 60 x 120 mm centred on its
-- origin; bh8_eigen.xml's two eigengrasps; bh8_contacts.xml's palm contact at (0, 0, -12)) or
-- from a second way of computing the same thing.

local function transpose_apply(pose, v) return graspkit.rotate_vector(pose, v) end  -- pose's axes

test("box bounds, vertices and max radius match its size", function()
  local world = graspkit.new_world()
  -- Turned 90 degrees about x: the box's 120 mm z extent lies along world y.
  local pose = graspkit.axis_angle({1, 0, 0}, math.pi / 2, {10, 20, 30})
  local box = world:add_object("objects/box.xml", pose)
  expect_near(box:bounds{frame = "body"}, {min = {-30, -30, -60}, max = {30, 30, 60}}, 1e-9)
  expect_near(box:bounds(), {min = {-20, -40, 0}, max = {40, 80, 60}}, 1e-9)
  expect_near(box:max_radius(), math.sqrt(30 ^ 2 + 30 ^ 2 + 60 ^ 2), 1e-9)
  local body_frame, world_frame = box:vertices{frame = "body"}, box:vertices()
  expect_true(#body_frame >= 8, "a box has at least its 8 corners")
  expect_equal(#world_frame, #body_frame)
  for i, p in ipairs(body_frame) do
    expect_near({math.abs(p[1]), math.abs(p[2]), math.abs(p[3])}, {30, 30, 60}, 1e-9)
    expect_near(world_frame[i], graspkit.transform_point(pose, p), 1e-9)
  end
  expect_error(function() box:bounds{frame = "camera"} end, "'world' or 'body'")
end)

test("look_at points z at the target with y up", function()
  local pose = graspkit.look_at({100, 0, 0}, {0, 0, 0})
  expect_near(graspkit.transform_point(pose, {0, 0, 100}), {0, 0, 0}, 1e-9)
  expect_near(transpose_apply(pose, {0, 1, 0}), {0, 0, 1}, 1e-9)
  expect_near(transpose_apply(pose, {1, 0, 0}), {0, -1, 0}, 1e-9)
  -- Looking straight down: `up` is along the line of sight, so y becomes the world y axis.
  local down = graspkit.look_at({0, 0, 100}, {0, 0, 0})
  expect_near(transpose_apply(down, {0, 0, 1}), {0, 0, -1}, 1e-9)
  expect_near(transpose_apply(down, {0, 1, 0}), {0, 1, 0}, 1e-9)
  expect_error(function() graspkit.look_at({1, 2, 3}, {1, 2, 3}) end, "the target is at the eye")
end)

test("eigengrasp amplitudes map to DOFs as bh8_eigen.xml says", function()
  local hand = graspkit.load_world("worlds/default.xml"):robot(1)
  local eg = hand:eigengrasps()
  expect_equal(#eg.grasps, 2)
  expect_false(eg.identity)
  local s = 1 / math.sqrt(3)  -- the file's (0, 1, 1, 1), normalised
  expect_near(eg.grasps[1].direction, {1, 0, 0, 0}, 1e-12)
  expect_near(eg.grasps[2].direction, {0, s, s, s}, 1e-12)
  local limits = hand:dof_limits()
  local a = {0.1, -0.2}
  hand:set_eigengrasp_amplitudes(a)
  for d = 1, 4 do
    local origin = (limits[d].min + limits[d].max) / 2  -- no ORIGIN in the file
    expect_near(eg.origin[d], origin, 1e-12)
    local expected = origin + a[1] * eg.grasps[1].direction[d] + a[2] * eg.grasps[2].direction[d]
    expect_near(hand:dofs()[d], expected, 1e-12, "DOF " .. d)
  end
  expect_near(hand:eigengrasp_amplitudes(), a, 1e-12)
  expect_error(function() hand:set_eigengrasp_amplitudes({1}) end, "2 amplitudes expected")
end)

test("virtual contacts sit where bh8_contacts.xml puts them", function()
  local hand = graspkit.load_world("worlds/default.xml"):robot(1)
  local contacts, derived = hand:virtual_contacts()
  expect_equal(#contacts, 9)
  expect_false(derived)
  local palm = contacts[1]
  expect_equal(palm.link, hand:base())
  expect_near(palm.point, graspkit.transform_point(hand:pose(), {0, 0, -12}), 1e-9)
  expect_near(palm.normal, graspkit.rotate_vector(hand:pose(), {0, 0, 1}), 1e-9)
  -- They move with the hand.
  hand:set_pose(graspkit.pose({5, 6, 7}))
  expect_near(hand:virtual_contacts()[1].point, {5, 6, -5}, 1e-9)
end)

test("collision switches turn a body and a pair off and back on", function()
  local world = graspkit.load_world("worlds/gripper_box.xml")
  local hand, box = world:robot(1), world:body("box")
  box:set_pose(hand:pose())  -- right through the palm
  expect_true(world:collides(box))
  world:set_collision(box, false)
  expect_false(world:collision_enabled(box))
  expect_false(world:collides(box))
  world:set_collision(box, true)
  expect_true(world:collides(box))
  world:set_collision(hand, false)
  expect_false(world:collision_enabled(hand))
  expect_false(world:collides(box), "the robot switched off")
  world:set_collision(hand, true)
  for _, link in ipairs(hand:links()) do world:set_collision(link, box, false) end
  expect_false(world:collides(box), "every hand-box pair switched off")
  expect_false(world:collision_enabled(hand:base(), box))
  expect_true(world:collision_enabled("floor", box), "other pairs untouched")
end)

test("removing a body renumbers the others and retires its Body objects", function()
  local world = graspkit.load_world("worlds/default.xml")
  local floor, mug = world:body("floor"), world:body("mug")
  world:set_collision(mug, false)
  world:remove_body(floor)
  expect_equal(#world:bodies(), 1)
  expect_equal(mug:name(), "mug", "a later body's object follows its body")
  expect_equal(world:body("mug"), mug)
  expect_false(world:collision_enabled(mug), "its switch followed it too")
  expect_error(function() return floor:name() end, "removed from its world")
  expect_error(function() return world:body("floor") end, "no body")
  expect_error(function() world:remove_body(world:robot(1):base()) end, "belongs to a robot")
end)

test("move_dofs_to_contacts closes toward targets and stops at the mug", function()
  local world = graspkit.load_world("worlds/default.xml")
  local hand = world:robot(1)
  local start = hand:dofs()
  local still = hand:move_dofs_to_contacts(start, {0.1, 0.1, 0.1, 0.1})
  expect_near(still.dofs, start, 1e-12, "targets at the start: nothing moves")
  local targets = {}
  for d, limit in ipairs(hand:dof_limits()) do targets[d] = d == 1 and start[1] or limit.max end
  local motion = hand:move_dofs_to_contacts(targets, {0, 0.05, 0.05, 0.05})
  expect_near(motion.dofs[1], start[1], 1e-12, "a zero step holds the spread")
  expect_true(#hand:contacts(world:body("mug")) > 0, "the fingers touch the mug")
  for d = 2, 4 do expect_true(motion.dofs[d] < targets[d], "finger " .. d .. " stopped early") end
  expect_error(function() hand:move_dofs_to_contacts({0}, {0}) end, "4 values expected")
end)

test("approach_to_contact follows a given direction", function()
  local world = graspkit.new_world()
  local hand = world:add_robot("robots/parallel_jaw/parallel_jaw.xml", graspkit.pose({-400, 0, 0}))
  local box = world:add_object("objects/box.xml")
  local function gap()
    local nearest = math.huge
    for _, link in ipairs(hand:links()) do nearest = math.min(nearest, (world:distance(link, box))) end
    return nearest
  end
  local start = hand:pose()
  local away, record = hand:approach_to_contact{direction = {-1, 0, 0}, max_distance = 50}
  expect_false(away, "moving away touches nothing")
  expect_equal(record.ended, "no_contact")
  expect_near(hand:pose().translation, {-450, 0, 0}, 1e-9, "the whole 50 mm, straight back")
  hand:set_pose(start)
  local touched = hand:approach_to_contact{direction = {2, 0, 0}, max_distance = 1000}
  expect_true(touched, "along +x the hand meets the box")
  local moved = hand:pose()
  expect_near({moved.translation[2], moved.translation[3]}, {0, 0}, 1e-9, "a straight line")
  expect_near(moved.quaternion, start.quaternion, 1e-12, "no turn")
  expect_true(moved.translation[1] > -400, "it moved toward the box")
  expect_true(gap() < 0.1, "it stops at contact, " .. gap() .. " mm away")
  expect_error(function() hand:approach_to_contact{direction = {0, 0, 0}} end, "is zero")
end)

test("a hand's search energy is what the list planner scores", function()
  local world = graspkit.load_world("worlds/default.xml")
  local hand, mug = world:robot(1), world:body("mug")
  local energy = hand:energy(mug, "contact")
  expect_true(energy >= 0, "the contact energy is a sum of distances and angles")
  local planner = graspkit.planner("list", {world = world, robot = hand, object = mug,
    energy = "contact", space = "complete", posture = "dof",
    states = {{pose = hand:pose(), dofs = hand:dofs()}}})
  planner:run{steps = 1}
  expect_near(planner:best()[1].energy, energy, 1e-9)
  mug:set_pose(hand:pose())
  local none, why = hand:energy(mug)
  expect_nil(none)
  expect_equal(why, "collides")
end)

test("a Lua energy that returns infinity fails at its own line", function()
  local world = graspkit.load_world("worlds/default.xml")
  local planner = graspkit.planner("simann", {world = world,
    energy = function(state) return math.huge end})
  local _, message = expect_error(function() planner:step(5) end, "returned inf")
  expect_true(message:find("energy function (", 1, true) ~= nil, message)
  expect_true(message:find("api_test.lua:", 1, true) ~= nil, "names the function's file: " .. message)
end)
