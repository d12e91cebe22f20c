#pragma once
// GraspIt!'s virtual-contact files (<virtualContacts>): contact points fixed on a hand's links.

#include <filesystem>
#include <vector>
#include "graspkit/model/virtual_contact.hpp"

namespace graspkit {

// The virtual contacts a file lists. Throws graspkit::Error naming file, line and element.
std::vector<VirtualContact> loadVirtualContactFile(const std::filesystem::path& file);

}  // namespace graspkit
