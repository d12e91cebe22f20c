#pragma once
// The one place graspkit sets up and tears down qhull: every hull (the grasp wrench space, a
// body's convex hull, a contact patch's outline) goes through runQhull, which keeps qhull's
// messages off the terminal and turns every failure into a message.

#include <functional>
#include <optional>
#include <string>
#include <vector>

extern "C" {
#include <libqhull_r/libqhull_r.h>
}

namespace graspkit::detail {

// Runs qhull with `options` (qhull options without the leading "qhull ") on the points of
// dimension `dim` packed in `coords` (qhull may joggle a copy; `coords` is not changed). On
// success calls `read` with the finished hull (its facet and vertex lists) before qhull's memory
// is freed, and returns nullopt; on failure returns "qhull: " and qhull's first error line.
// Thread-safe: each call has its own qhull state.
std::optional<std::string> runQhull(std::vector<double>& coords, int dim, const char* options,
                                    const std::function<void(qhT* qh)>& read);

}  // namespace graspkit::detail
