#pragma once
// The world `graspkit serve` holds, and the actions of its JSON API (docs/editor.md): each
// action takes a JSON object and answers one, so the same calls serve the page, scripts and the
// latency bench. The session moves the hand, closes it, measures the grasp after every change,
// keeps undo and redo, saves, plans in the background and validates. It knows nothing of HTTP.

#include <atomic>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "graspkit/base/error.hpp"
#include "graspkit/host/world_session.hpp"
#include "graspkit/lua/sandbox.hpp"
#include "graspkit/model/body_ref.hpp"
#include "graspkit/planning/hand_configuration.hpp"

namespace graspkit::cli {

// A request the API refuses because of what it asks (a bad argument, an unknown action):
// nothing was changed. `status` is the HTTP status the server answers with.
class RequestError : public Error {
 public:
  RequestError(int status, const std::string& message) : Error(message), status_(status) {}
  int status() const { return status_; }

 private:
  int status_;
};

// A grasp the page can step through: from a plan file or from a plan run in the session.
struct EditorGrasp {
  std::string name;
  HandConfiguration hand;  // the closed hand
  nlohmann::json summary;  // energy, epsilon, volume, contacts, force_closure
};

struct EditorOptions {
  LoadOptions load;
  lua::PathPolicy files;  // what load, save and picture may read and write
  std::size_t undoDepth = 200;
};

class EditorSession {
 public:
  // `input` is a world file, or a plan (plan --out) whose grasps the page steps through.
  EditorSession(const std::filesystem::path& input, EditorOptions options);
  ~EditorSession();
  EditorSession(const EditorSession&) = delete;
  EditorSession& operator=(const EditorSession&) = delete;

  // Runs action `name` with `args` (an object) and returns its answer. Throws RequestError for a
  // bad request and graspkit::Error for what the engine refuses; either way the world is as it
  // was before the call.
  nlohmann::json act(std::string_view name, const nlohmann::json& args);

  // The world's bodies as binary glTF (one node per body, named as the state's "bodies").
  std::string sceneGltf() const;
  // A PNG of the world through the engine's renderer (args as the "picture" action's).
  std::string picturePng(const nlohmann::json& args) const;

  // The names act() knows, for the documentation and the server's refusals.
  static const std::vector<std::string>& actionNames();

 private:
  struct PlanRun;

  // The world as the page shows it. A preview (a drag's or a slider's intermediate request)
  // measures epsilon by the nearest facet (exact, no volume); otherwise with GraspIt!'s qhull.
  nlohmann::json state(bool preview = false) const;
  nlohmann::json changed(const char* group, const nlohmann::json& args, World next,
                         nlohmann::json extra = nlohmann::json::object());
  nlohmann::json undo(bool forward);
  nlohmann::json save(const nlohmann::json& args);
  nlohmann::json load(const nlohmann::json& args);
  nlohmann::json picture(const nlohmann::json& args) const;
  nlohmann::json script(const nlohmann::json& args) const;
  nlohmann::json plan(const nlohmann::json& args);
  nlohmann::json planStatus() const;
  nlohmann::json planStop();
  nlohmann::json grasps() const;
  nlohmann::json showGrasp(const nlohmann::json& args);
  nlohmann::json validate(const nlohmann::json& args) const;
  nlohmann::json simulate(const nlohmann::json& args) const;
  void collectPlan();
  void open(const std::filesystem::path& input);

  EditorOptions options_;
  mutable std::mutex mutex_;  // the world, the undo lists and the grasps
  host::WorldSession session_;
  int hand_ = 0;
  std::optional<BodyRef> object_;  // none: a bare hand to shape (no grasp to measure)
  const BodyRef& object() const;   // throws RequestError (409) when there is none
  std::vector<World> undo_, redo_;
  std::string lastGroup_;  // a drag's requests share one undo step
  std::vector<EditorGrasp> grasps_;
  std::unique_ptr<PlanRun> plan_;
};

}  // namespace graspkit::cli
