#pragma once
// GraspIt!'s pre-XML side files, turned into the XML forms GraspIt! 2.1 reads (what its
// xmlconverter did): eigengrasp files (.egr) and virtual-contact files (.vgr). Numbers are carried
// over as written, so a conversion loses nothing and gives the same bytes every time.
//
// .egr: `DIMENSIONS n`, then blocks `EG`, `ORIGIN` or `NORM`, each an eigenvalue and n numbers.
// Numbers after the last block belong to none (GraspIt!'s reader stops there); they are left out
// with a warning.
// .vgr: the robot's name, the contact count, then per contact: finger and link, the friction-edge
// count, the edges (6 numbers each), location (3), rotation (w x y z), translation (3), normal
// (3) and the friction coefficient.
//
// The older .cfg robot and .wld world grammars have no public description; graspkit does not
// guess at them.

#include <filesystem>
#include <string>

namespace graspkit {

// Each throws graspkit::Error naming the file and line of the first token it cannot use.
std::string eigengraspXmlFromEgr(const std::filesystem::path& egr);
std::string virtualContactXmlFromVgr(const std::filesystem::path& vgr);

}  // namespace graspkit
