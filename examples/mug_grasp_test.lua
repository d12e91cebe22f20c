-- mug_grasp_test.lua: scenario tests as a user writes them, on the default world (the bh8 hand
-- above a mug standing on a floor). Each test(name, fn) is one test; expect_* record a failure
-- and let the test go on; an error ends the test. Every expected value comes from the model
-- files or from a hand calculation, never from a run of graspkit.
--
-- Run from the repository root (--root models lets the tests read the project's models):
--   graspkit test examples/mug_grasp_test.lua --root models

local WORLD = graspkit.script_folder .. "/../models/worlds/default.xml"

-- From models/objects/mug.xml and mug.iv: a cylinder of radius 40 and height 100 centred on
-- the mug's origin, a handle on +x of two arms 30 x 14 x 10 at z = +-30 (x = 40..70) and a grip
-- 10 x 14 x 50 (x = 60..70). default.xml stands it at (0, 0, 50); the floor's top is z = 0.
local MUG_RADIUS, MUG_HEIGHT, MUG_Z = 40, 100, 50
local CONTACT_THRESHOLD = 0.2  -- mm, GraspIt!'s Contact::THRESHOLD

local function load()
  return graspkit.load_world(WORLD)
end

local function length(v)
  return math.sqrt(v[1] ^ 2 + v[2] ^ 2 + v[3] ^ 2)
end

test("the mug stands on the floor", function()
  local world = load()
  local mug = world:body("mug")
  expect_equal(mug:kind(), "graspable")
  expect_equal(world:body("floor"):kind(), "obstacle")
  -- Its lowest point is half its height below its origin: exactly at the floor's top.
  expect_near(mug:pose().translation[3] - MUG_HEIGHT / 2, 0, 1e-9)
  expect_near(world:distance("mug", "floor"), 0, 1e-6)
end)

test("the mug's mass properties are those of its file", function()
  local mug = load():body("mug")
  expect_equal(mug:material(), "glass")
  expect_near(mug:mass(), 350, 1e-9)
  -- The centre of mass of the solid (uniform density): cylinder at x = 0, arms centred at
  -- x = 55, grip at x = 65.
  local cylinder = math.pi * MUG_RADIUS ^ 2 * MUG_HEIGHT
  local arms, grip = 2 * 30 * 14 * 10, 10 * 14 * 50
  local cog_x = (arms * 55 + grip * 65) / (cylinder + arms + grip)
  expect_near(mug:cog(), {cog_x, 0, 0}, 1e-4)
end)

test("rays straight down meet the mug where its geometry says", function()
  local world = load()
  -- Below the hand (its palm is above z = 200), above the mug's top (z = 100).
  local down = {0, 0, -1}
  local hit = world:raycast({0, 0, 150}, down)
  expect_not_nil(hit)
  if hit then
    expect_equal(hit.body:name(), "mug")
    expect_near(hit.point, {0, 0, MUG_Z + MUG_HEIGHT / 2}, 1e-6)
    expect_near(hit.distance, 150 - (MUG_Z + MUG_HEIGHT / 2), 1e-6)
    expect_near(hit.normal, {0, 0, 1}, 1e-6)
  end
  -- Over the handle: the top face of its upper arm, z = 50 + 30 + 10 / 2.
  hit = world:raycast({55, 0, 150}, down)
  expect_equal(hit and hit.body:name(), "mug")
  expect_near(hit and hit.point[3], MUG_Z + 30 + 5, 1e-6)
  -- Past the handle (x = 70) the ray reaches the floor.
  hit = world:raycast({75, 0, 150}, down)
  expect_equal(hit and hit.body:name(), "floor")
  expect_near(hit and hit.point[3], 0, 1e-6)
  -- A ray shorter than the gap to the mug's top meets nothing.
  expect_nil(world:raycast({0, 0, 150}, down, {max_distance = 40}))
end)

test("the fingertips are where the bh8's dimensions put them", function()
  local hand = load():robot("bh8")
  hand:set_pose(graspkit.identity())
  -- models/README.md: a 50 mm knuckle, a 70 mm inner link at +5 degrees and a 50 mm fingertip
  -- at +45 degrees (40 + flexion / 3); fingers 1 and 2 on the spread axes at x = +-25.
  local reach = 50 + 70 * math.cos(math.rad(5)) + 50 * math.cos(math.rad(45))
  local height = 70 * math.sin(math.rad(5)) + 50 * math.sin(math.rad(45))
  hand:set_dofs({0, 0, 0, 0})
  local tips = hand:link_poses()
  expect_near(tips[1][3].translation, {25, reach, height}, 1e-6)
  expect_near(tips[2][3].translation, {-25, reach, height}, 1e-6)
  expect_near(tips[3][2].translation, {0, -reach, height}, 1e-6)
  -- Spread 90 degrees turns fingers 1 and 2 outwards along +-x.
  hand:set_dofs({math.pi / 2, 0, 0, 0})
  tips = hand:link_poses()
  expect_near(tips[1][3].translation, {25 + reach, 0, height}, 1e-6)
  expect_near(tips[2][3].translation, {-25 - reach, 0, height}, 1e-6)
end)

test("autograsp closes the hand on the mug without piercing it", function()
  local world = load()
  local hand = world:robot(1)
  local mug = world:body("mug")
  local motion = hand:autograsp()
  expect_true(#motion.contacts >= 3, "at least one contact per finger")
  for i, contact in ipairs(motion.contacts) do
    local note = "contact " .. i
    expect_equal(contact.body1:kind(), "link", note)
    expect_true(contact.body2 == mug, note)
    expect_true(contact.distance >= 0 and contact.distance <= CONTACT_THRESHOLD, note)
    local gap = {contact.point2[1] - contact.point1[1], contact.point2[2] - contact.point1[2],
                 contact.point2[3] - contact.point1[3]}
    expect_near(length(gap), contact.distance, 1e-6, note)
    -- Rubber fingers on a glass mug: GraspIt!'s friction table gives 1.0.
    expect_near(contact.mu, 1.0, 1e-12, note)
    -- The point on the mug lies on its side, within the tessellation's 1 mm of radius 40.
    local p = contact.point2
    expect_near(math.sqrt(p[1] ^ 2 + p[2] ^ 2), MUG_RADIUS, 1.0, note)
    expect_true(p[3] >= 0 and p[3] <= MUG_HEIGHT + 1e-6, note)
  end
  for _, link in ipairs(hand:links()) do
    expect_false(world:collides(link, mug), link:name() .. " intersects the mug")
  end
  -- Every finger stopped on the mug, before the end of its range.
  local limits = hand:dof_limits()
  for d = 2, 4 do
    expect_true(hand:dofs()[d] < limits[d].max, "DOF " .. d)
  end
  -- Three rubber fingertips around the rim hold the mug; epsilon > 0 is force closure.
  local grasp = hand:grasp(mug)
  expect_true(grasp:force_closure())
  expect_equal(grasp:epsilon() > 0, grasp:force_closure())
  expect_equal(grasp:contact_count(), #motion.contacts)
end)

test("a clone is independent of its original", function()
  local world = load()
  local copy = world:clone()
  copy:body("mug"):set_pose(graspkit.pose({0, 0, 500}))
  copy:robot(1):set_dofs({1, 1, 1, 1})
  expect_near(world:body("mug"):pose().translation, {0, 0, MUG_Z}, 0)
  expect_near(world:robot(1):dofs(), {0, 0.2, 0.2, 0.2}, 1e-12)
  expect_near(copy:body("mug"):pose().translation, {0, 0, 500}, 0)
  expect_true(world:body("mug") ~= copy:body("mug"))
  expect_error(function() world:distance(copy:body("mug"), "floor") end, "another world")
end)

test("bad requests raise errors that say what is wrong", function()
  local world = load()
  local hand = world:robot(1)
  expect_error(function() hand:set_dofs({0, 0}) end, "4 DOF values expected")
  expect_error(function() hand:set_dofs({0, 5, 0, 0}, {limits = "error"}) end, "outside")
  expect_error(function() hand:autograsp({sped = 2}) end, "unknown option 'sped'")
  expect_error(function() world:robot(2) end, "out of range")
  expect_error(function() world:body("teapot") end, "no body or link 'teapot'")
  expect_error(function() hand:link(1, 1):set_pose(graspkit.identity()) end, "move its robot")
  expect_error(function() graspkit.load_world("no_such_world.xml") end, "no_such_world.xml")
end)

test("DOF values are clamped to the joint limits by default", function()
  local hand = load():robot(1)
  hand:set_dofs({0, 5, 0, 0})
  -- models/README.md: flexion joints range over 0..140 degrees.
  expect_near(hand:dofs()[2], math.rad(140), 1e-9)
  hand:set_dofs({0, -1, 0, 0})
  expect_near(hand:dofs()[2], 0, 0)
end)

test("poses compose as rigid motions", function()
  local quarter = graspkit.axis_angle({0, 0, 1}, math.pi / 2, {10, 0, 0})
  expect_near(graspkit.transform_point(quarter, {1, 0, 0}), {10, 1, 0}, 1e-12)
  expect_near(graspkit.rotate_vector(quarter, {1, 0, 0}), {0, 1, 0}, 1e-12)
  local moved, turned = graspkit.pose_distance(quarter * graspkit.inverse(quarter),
                                               graspkit.identity())
  expect_near(moved, 0, 1e-12)
  expect_near(turned, 0, 1e-7)
  -- Two quarter turns are a half turn: w = cos(pi / 2) = 0, z = sin(pi / 2) = 1.
  local half = graspkit.compose(quarter, quarter)
  expect_near(half.quaternion, {0, 0, 0, 1}, 1e-12)
  expect_near(half.translation, {10, 10, 0}, 1e-12)
end)
