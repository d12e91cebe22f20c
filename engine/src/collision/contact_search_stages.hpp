#pragma once
// Internal: the contact search with its stages chosen by the caller, for tests that hold the
// search in two stages to the search in one (ContactRequest::firstStageThreshold).

#include <optional>

#include "graspkit/collision/contact_search.hpp"

namespace graspkit::collision {

// findContacts with two stages (true: wherever the request allows them), one (false), or as
// findContacts chooses (nullopt: two where the pair was dense at its last search).
ContactResult findContactsInStages(const World& world, const BodyRef& body1, const BodyRef& body2,
                                   const ContactRequest& request, std::optional<bool> two_stages);

}  // namespace graspkit::collision
