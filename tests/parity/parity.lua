-- The parity request through Lua (tests/parity/parity_test.py runs it with `graspkit run
-- parity.lua --json --root ROOT --allow-read WORK -- PLANNER_WORLD GRASP_WORLD STEPS SEED TOP
-- SECONDS DATASET`). Returns parity_test.py's schema: plan, grasp, validation, simulation, and
-- the dataset `graspkit batch` wrote (Lua reads datasets; it does not plan them).

local planner_world, grasp_world = arg[1], arg[2]
local steps, seed, top, seconds = tonumber(arg[3]), tonumber(arg[4]), tonumber(arg[5]),
    tonumber(arg[6])

local function pose7(pose)
  local t, q = pose.translation, pose.quaternion
  return {t[1], t[2], t[3], q[1], q[2], q[3], q[4]}
end

local world = graspkit.load_world(planner_world)
local planner = graspkit.planner("simann", {world = world, seed = seed, top = top})
planner:run{steps = steps}
local plan = {}
for i, g in ipairs(planner:finish()) do
  plan[i] = {epsilon = g.epsilon, volume = g.volume, contacts = g.contacts,
             force_closure = g.force_closure, pose = pose7(g.world:robot(1):pose())}
end

local closed = graspkit.load_world(planner_world)
local hand = closed:robot(1)
hand:autograsp()
local measured = hand:grasp()
local grasp = {epsilon = measured:epsilon(), volume = measured:volume(),
               contacts = measured:contact_count(), force_closure = measured:force_closure()}

local held = graspkit.load_world(grasp_world):validate{seconds = seconds}
local slip = {}
for i, d in ipairs(held.directions) do slip[i] = d.slip_mm end
local validation = {held = held.held, directions_held = held.directions_held,
                    settle_seconds = held.settle_seconds, slip = slip}

local moving = graspkit.load_world(grasp_world)
local run = moving:simulate{seconds = seconds, autograsp = true}
local bodies, dofs = {}, {}
for i, b in ipairs(moving:bodies()) do bodies[i] = pose7(b:pose()) end
for _, r in ipairs(moving:robots()) do
  for _, v in ipairs(r:dofs()) do dofs[#dofs + 1] = v end
end
local simulation = {completed = true, steps = run.steps, time = run.time, bodies = bodies,
                    dofs = dofs}

local dataset = {}
for i, g in ipairs(graspkit.load_dataset(arg[7]).grasps) do
  dataset[i] = {epsilon = g.epsilon, volume = g.volume, force_closure = g.force_closure,
                pose = pose7(g.pose)}
end

return {plan = plan, grasp = grasp, validation = validation, simulation = simulation,
        dataset = dataset}
