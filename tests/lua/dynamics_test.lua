-- Dynamics from Lua on the project's own models (run with --root models): a free fall against
-- its closed form, the box landing on the floor and staying, gravity switched off as in GraspIt!,
-- velocities set and read back, and the errors of bad input. floor.xml's top face is z = 0 and
-- box.xml is 60 x 60 x 120 mm centred on its origin (so it rests with its centre at z = 60).

test("a box falls along z0 - g t^2 / 2", function()
  local world = graspkit.new_world()
  local box = world:add_object("objects/box.xml", graspkit.pose({0, 0, 2000}))
  expect_near(world:gravity(), {0, 0, -9810}, 0)
  local report = world:simulate{seconds = 0.5}
  expect_equal(report.steps, 200)
  expect_near(world:time(), 0.5, 1e-12)
  local drop = 9810 * 0.5 ^ 2 / 2
  expect_near(box:pose().translation[3], 2000 - drop, 1e-3 * drop)
  local v, w = box:velocity()
  expect_near(v, {0, 0, -9810 * 0.5}, 1e-6)
  expect_near(w, {0, 0, 0}, 1e-12)
end)

test("the box lands on the floor and stays there", function()
  local world = graspkit.new_world()
  world:add_obstacle("obstacles/floor.xml")
  local box = world:add_object("objects/box.xml", graspkit.pose({0, 0, 100}))
  world:simulate{seconds = 1}
  local z = box:pose().translation[3]
  expect_near(z, 60.1, 0.05)  -- resting 0.1 mm above the floor
  world:simulate{seconds = 2}
  expect_near(box:pose().translation[3], z, 0.1)
end)

test("without gravity a box keeps the velocity it is given", function()
  local world = graspkit.new_world()
  world:set_gravity{0, 0, 0}
  local box = world:add_object("objects/box.xml")
  box:set_velocity({10, 0, 0}, {0, 0, 0})
  for _ = 1, 40 do world:step() end
  expect_near(box:pose().translation, {1.0, 0, 0}, 1e-9)  -- 10 mm/s for 0.1 s
end)

test("bad input is an error, not a crash", function()
  local world = graspkit.new_world()
  local floor = world:add_obstacle("obstacles/floor.xml")
  expect_error(function() world:step(0) end, "time step")
  expect_error(function() world:step(1) end, "time step")
  expect_error(function() floor:set_velocity({1, 0, 0}) end, "not a graspable body")
  expect_error(function() world:set_gravity{0, 0} end, "")
  local box = world:add_object("objects/box.xml", graspkit.pose({0, 0, 30}))  -- in the floor
  expect_error(function() world:step() end, "interpenetrate")
end)
