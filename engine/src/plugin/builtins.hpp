#pragma once
// The engine's own factories, registered by every Registry at construction.

namespace graspkit {

class Registry;

void addBuiltinQualityMeasures(Registry& registry);  // grasp/quality.cpp
void addBuiltinRobotTypes(Registry& registry);       // model/robot_type.cpp
void addBuiltinSearchEnergies(Registry& registry);   // planning/search_energies.cpp

}  // namespace graspkit
