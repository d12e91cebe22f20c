-- GraspIt!'s own figures (../shared/reference/graspit-figures.json) reproduced through the Lua
-- API, as a user checking graspkit against GraspIt! would write it. The corpus is found through
-- GRASPKIT_SHARED (set by the ctest that runs this file); without it every test is skipped.

local shared = os.getenv("GRASPKIT_SHARED")

local function needShared()
  if not shared or not io.open(shared .. "/reference/graspit-figures.json") then
    skip("SKIPPED: the GraspIt! corpus (../shared) was not found; set GRASPKIT_SHARED")
  end
end

local function reference()
  local file = assert(io.open(shared .. "/reference/graspit-figures.json"))
  local figures = graspkit.json_decode(file:read("a"))
  file:close()
  return figures
end

local function poseOf(tran)
  return graspkit.pose(tran.t_mm, tran.q_wxyz)
end

-- Every link of every configuration GraspIt! recorded, at its DOF values: position within
-- 1e-6 mm and orientation within 1e-6 rad.
test("link poses match GraspIt!'s forward kinematics", function()
  needShared()
  for file, robot in pairs(reference().forward_kinematics) do
    local world = graspkit.new_world()
    local hand = world:add_robot(shared .. "/graspit-data/" .. file)
    for name, config in pairs(robot.configs) do
      -- Configurations without requested values are the robot as loaded: its recorded DOFs.
      hand:set_dofs(config.requested_dof_values or config.state.dof_values, {limits = "ignore"})
      expect_near(hand:dofs(), config.state.dof_values, 1e-9, file .. " " .. name .. " dofs")
      for d, dof in ipairs(config.state.dofs) do
        expect_near(hand:dof_limits()[d].min, dof.min, 1e-9, file .. " dof " .. d .. " min")
        expect_near(hand:dof_limits()[d].max, dof.max, 1e-9, file .. " dof " .. d .. " max")
      end
      local poses = hand:link_poses()
      expect_equal(#poses, #config.state.chains, file .. " chains")
      for c, chain in ipairs(config.state.chains) do
        for l, link in ipairs(chain.links) do
          local distance, angle = graspkit.pose_distance(poses[c][l], poseOf(link.tran))
          expect_near(distance, 0, 1e-6, file .. " " .. name .. " " .. link.name .. " position")
          expect_near(angle, 0, 1e-6, file .. " " .. name .. " " .. link.name .. " rotation")
        end
      end
    end
  end
end)

-- The force-closure grasp of the plannerMug world: autograsp from GraspIt!'s start, then the
-- same final DOFs (1e-6), contact count, and epsilon and volume within 1%.
test("plannerMug force-closure grasp matches GraspIt!", function()
  needShared()
  local entry = reference().grasps.plannerMug_force_closure_1
  local world = graspkit.load_world(shared .. "/graspit-data/worlds/plannerMug.xml")
  local hand = world:robot(1)
  hand:set_pose(poseOf(entry.hand_pose_before))
  hand:set_dofs(entry.hand_dofs_before)
  local motion = hand:autograsp()
  expect_near(motion.dofs, entry.autograsp.final_dofs, 1e-6)
  local grasp = hand:grasp(world:body("mug"))
  expect_equal(grasp:contact_count(), entry.autograsp.num_contacts)
  expect_near(grasp:epsilon(), entry.autograsp.epsilon_L1, 0.01 * entry.autograsp.epsilon_L1)
  expect_near(grasp:volume(), entry.autograsp.volume_L1, 0.01 * entry.autograsp.volume_L1)
  expect_true(grasp:force_closure())
end)

-- As loaded, the hand closes on the mug without force closure: GraspIt! reports epsilon -1.
test("plannerMug as loaded is not force closure, as in GraspIt!", function()
  needShared()
  local entry = reference().grasps.plannerMug_as_loaded
  local world = graspkit.load_world(shared .. "/graspit-data/worlds/plannerMug.xml")
  local hand = world:robot(1)
  local motion = hand:autograsp()
  expect_near(motion.dofs, entry.autograsp.final_dofs, 1e-6)
  local grasp = hand:grasp("mug")
  expect_equal(grasp:contact_count(), entry.autograsp.num_contacts)
  expect_equal(grasp:epsilon(), -1)
  expect_false(grasp:force_closure())
end)

-- Puma560's closed-form inverse kinematics: the end of the chain lands on the target it was
-- given (forward kinematics of the answer), from a pose the arm reached itself.
test("Puma560 inverse kinematics reaches its own forward kinematics", function()
  needShared()
  local world = graspkit.new_world()
  local arm = world:add_robot(shared .. "/graspit-data/models/robots/Puma560/Puma560.xml")
  expect_false(arm:is_hand())
  arm:set_dofs({0.4, -0.6, 0.9, 0.3, 0.7, -0.2})
  local poses = arm:link_poses()
  local target = poses[1][#poses[1]]
  arm:set_dofs({0.3, -0.5, 0.8, 0.2, 0.6, -0.1})
  local dofs, why = arm:inverse_kinematics(target)
  expect_not_nil(dofs, why)
  arm:set_dofs(dofs)
  poses = arm:link_poses()
  local distance, angle = graspkit.pose_distance(poses[1][#poses[1]], target)
  expect_near(distance, 0, 1e-6)
  expect_near(angle, 0, 1e-6)
  -- Out of reach: nil and a reason, not an error.
  local none, reason = arm:inverse_kinematics(graspkit.pose({5000, 0, 0}))
  expect_nil(none)
  expect_true(type(reason) == "string" and #reason > 0)
end)
