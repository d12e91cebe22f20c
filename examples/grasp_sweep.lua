-- grasp_sweep: the code sweep_quality.lua and save_best_grasp.lua share, as a Lua module beside
-- them (`local sweep = require("grasp_sweep")` finds it in the script's folder).
--
-- A sweep places a hand at evenly spaced angles around an object's vertical axis, each time in
-- a fresh clone of the world: the palm's approach direction (+z of the palm frame) points at the
-- axis, the fingers close horizontally. At each angle the hand opens, moves along its approach
-- direction until it touches something, closes (autograsp), and the grasp's quality is measured.

local sweep = {}

-- Where the hand starts for one angle (radians about world +z, 0 = along +x): `distance` mm
-- from the object's axis, `lift` mm above the object's origin, approach direction horizontal
-- and towards the axis.
function sweep.start_pose(center, angle, distance, lift)
  local position = {
    center[1] + distance * math.cos(angle),
    center[2] + distance * math.sin(angle),
    center[3] + lift,
  }
  -- Read right to left: turn the palm's +z onto world -x (-90 degrees about y), then turn that
  -- about the vertical by `angle` and move it into place, so the approach points at the axis.
  return graspkit.compose(graspkit.axis_angle({0, 0, 1}, angle, position),
                          graspkit.axis_angle({0, 1, 0}, -math.pi / 2))
end

-- One grasp attempt in `world` (changed in place): place, open, approach, close, measure.
-- Returns a record of what happened; `world` is kept in it, holding the grasp.
function sweep.try(world, hand_index, object_name, pose)
  local hand = world:robot(hand_index)
  hand:set_pose(pose)
  local opened = hand:open()
  local touched = hand:approach_to_contact()
  local motion = hand:autograsp()
  local grasp = hand:grasp(object_name)
  return {
    world = world,
    opened = opened,
    touched = touched,
    contacts = grasp:contact_count(),
    epsilon = grasp:epsilon(),
    volume = grasp:volume(),
    force_closure = grasp:force_closure(),
    failure = grasp:failure(),  -- why no wrench space could be built, or nil
    pose = hand:pose(),
    dofs = motion.dofs,
  }
end

-- Runs a sweep over `options.count` angles (default 12) and returns one record per angle, in
-- order, each with its `angle` in radians. Options: hand (robot index, default 1), object
-- (name, default "mug"), distance (mm from the axis, default 200), lift (mm, default 10).
function sweep.run(base_world, options)
  options = options or {}
  local count = options.count or 12
  local hand_index = options.hand or 1
  local object_name = options.object or "mug"
  local distance = options.distance or 200
  local lift = options.lift or 10
  local center = base_world:body(object_name):pose().translation
  local records = {}
  for i = 1, count do
    local angle = 2 * math.pi * (i - 1) / count
    local pose = sweep.start_pose(center, angle, distance, lift)
    local record = sweep.try(base_world:clone(), hand_index, object_name, pose)
    record.angle = angle
    records[#records + 1] = record
    graspkit.progress(i, count, "sweep")
  end
  return records
end

-- The record with the largest epsilon (the first of equals), or nil for an empty list.
function sweep.best(records)
  local best = nil
  for _, record in ipairs(records) do
    if best == nil or record.epsilon > best.epsilon then best = record end
  end
  return best
end

-- Prints the records as a table: angle (degrees), contacts, epsilon, volume, force closure.
-- An angle whose wrench space could not be built is starred, its reason printed below.
function sweep.print_table(records)
  print(string.format("%9s %9s %10s %10s %14s", "angle deg", "contacts", "epsilon", "volume",
                      "force closure"))
  local notes = {}
  for _, r in ipairs(records) do
    local star = r.failure and " *" or ""
    print(string.format("%9.1f %9d %10.4f %10.4f %14s%s", math.deg(r.angle), r.contacts,
                        r.epsilon, r.volume, r.force_closure and "yes" or "no", star))
    if r.failure then
      notes[#notes + 1] = string.format("* %.1f: %s", math.deg(r.angle), r.failure)
    end
  end
  for _, note in ipairs(notes) do print(note) end
end

return sweep
