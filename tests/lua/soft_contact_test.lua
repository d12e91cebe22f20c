-- Soft-finger contacts through the Lua API, on GraspIt!'s own files: its rubber-like sphere
-- (models/objects/sphere.xml: radius 8 mm, <youngs> 1.5e6 Pa) resting on its floor. The
-- truth is the closed form for a sphere on a plane: relative radii R' = 8 mm both ways, and the
-- mattress model (depth 3 mm, 5 N) gives e_tau = 8/15 sqrt(2 delta R') with
-- delta = sqrt(5 * 0.003 / (1.5e6 * pi * 0.008)) m, that is 1.6943 mm.

local shared = os.getenv("GRASPKIT_SHARED")

local function needShared()
  if not shared or not io.open(shared .. "/graspit-data/models/objects/sphere.xml") then
    skip("SKIPPED: the GraspIt! corpus (../shared) was not found; set GRASPKIT_SHARED")
  end
end

-- The sphere 0.1 mm above the floor, found with rays (the floor first, the sphere away from it).
local function sphereOnFloor()
  local world = graspkit.new_world()
  world:add_obstacle(shared .. "/graspit-data/models/obstacles/simpleFloor.xml")
  local ball = world:add_object(shared .. "/graspit-data/models/objects/sphere.xml",
                                graspkit.pose({3000, 3000, 0}))
  local floor_top = world:raycast({100, 100, 1000}, {0, 0, -1})
  local ball_bottom = world:raycast({3000, 3000, -100}, {0, 0, 1})
  expect_equal(floor_top.body:name(), "simpleFloor", "the first ray meets the floor")
  expect_equal(ball_bottom.body:name(), "sphere", "the second ray meets the sphere")
  ball:set_pose(graspkit.pose({100, 100, floor_top.point[3] + 0.1 - ball_bottom.point[3]}))
  return world
end

test("a soft sphere on a floor is one soft contact with the sphere's e_tau", function()
  needShared()
  local contacts = sphereOnFloor():contacts()
  -- Every touching vertex lies within one patch (3.5 mm at 1.5e6 Pa): they merge into one.
  expect_equal(#contacts, 1, "contacts")
  local c = contacts[1]
  expect_equal(c.model, "soft_finger", "model")
  expect_near(c.distance, 0.1, 1e-6, "distance")
  -- Coin meshes the sphere with 390 triangles; the fit sees a slightly flatter cap, and e_tau
  -- goes with the fourth root of the radius: 5 % covers it.
  expect_near(c.torsion, 1.6943, 0.05 * 1.6943, "e_tau, mm")
end)
