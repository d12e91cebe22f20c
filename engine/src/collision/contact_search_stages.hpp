#pragma once
// Internal: the contact search with its stages, and where it finds its candidate triangle pairs,
// chosen by the caller, for tests that hold each way to the other (the stages:
// ContactRequest::firstStageThreshold).

#include <optional>

#include "graspkit/collision/contact_search.hpp"

namespace graspkit::collision {

// findContacts with two stages (true: wherever the request allows them), one (false), or as
// findContacts chooses (nullopt: two where the pair was dense at its last search).
ContactResult findContactsInStages(const World& world, const BodyRef& body1, const BodyRef& body2,
                                   const ContactRequest& request, std::optional<bool> two_stages);

// On this thread, until set back to nullopt: each query triangle's candidates found from the
// target's triangles (true), from its own ball (false), or as the search chooses (nullopt: from
// the target's where the query's triangles are over twice the size of the target's).
void setCandidatesFromTarget(std::optional<bool> from_target);

}  // namespace graspkit::collision
