# examples/report_world.lua reports what the model files say: the default world's floor
# (obstacle, wood), mug (object, glass, 350 g, at z = 50) and bh8 hand (at z = 190, turned 180
# degrees about x; spread 0..180 degrees, flexion 0..140 degrees, flexion DOFs at 0.2 rad; a palm
# and 3 + 3 + 2 links), the mug touching the floor; and, given gripper_box.xml, the
# parallel-jaw gripper's 0..40 mm DOF (models/README.md).
include(${CMAKE_CURRENT_LIST_DIR}/example_support.cmake)

run_example(out run report_world.lua)
expect_output("${out}" "floor: obstacle, wood" "the floor")
expect_output("${out}" "mug: graspable, glass, 350\\.0 g" "the mug")
expect_output("${out}" "mug: [^\n]*\n +pose \\(0\\.00, 0\\.00, 50\\.00\\) mm, q = \\(1\\.0000, 0\\.0000, 0\\.0000, 0\\.0000\\)"
              "the mug's pose")
expect_output("${out}" "bh8: type Hand [^\n]*a hand, 3 chains\n +pose \\(0\\.00, 0\\.00, 190\\.00\\) mm, q = \\(0\\.0000, 1\\.0000, 0\\.0000, 0\\.0000\\)"
              "the hand and its pose")
expect_output("${out}" "DOF 1 = 0\\.0000 in \\[0\\.0000, 3\\.1416\\]" "the spread DOF")
foreach(dof 2 3 4)
  expect_output("${out}" "DOF ${dof} = 0\\.2000 in \\[0\\.0000, 2\\.4435\\]" "flexion DOF ${dof}")
endforeach()
expect_output("${out}" "links: bh8_palm, bh8_chain0_link0, bh8_chain0_link1, bh8_chain0_link2, bh8_chain1_link0, bh8_chain1_link1, bh8_chain1_link2, bh8_chain2_link0, bh8_chain2_link1\n"
              "a palm and 3 + 3 + 2 links")
expect_output("${out}" "contacts [^\n]*\n +floor - mug: [1-9][0-9]* contacts" "the mug on the floor")

run_example(out run report_world.lua ARGS models/worlds/gripper_box.xml)
expect_output("${out}" "box: graspable, plastic, 300\\.0 g" "the box")
expect_output("${out}" "parallel_jaw: type Hand" "the gripper")
expect_output("${out}" "DOF 1 = 0\\.0000 in \\[0\\.0000, 40\\.0000\\]" "the gripper's DOF")
