// graspkit serve: place a hand, shape it and see the grasp in the browser (docs/editor.md).
#include "commands/serve_command.hpp"

#include <cstdlib>

#include "serve/editor_server.hpp"
#include "serve/editor_session.hpp"
#include "support/argument_checks.hpp"

namespace graspkit::cli {

namespace {

// What load may read: the model roots (--root, $GRASPKIT_ROOT, $GRASPIT), the folder above the
// world's (GraspIt!'s worlds/ beside models/), and the folders given.
std::vector<std::filesystem::path> readableFolders(const ServeOptions& options) {
  std::vector<std::filesystem::path> folders = options.load.roots;
  for (const char* variable : {"GRASPKIT_ROOT", "GRASPIT"})
    if (const char* root = std::getenv(variable); root != nullptr && *root != '\0')
      folders.emplace_back(root);
  const std::filesystem::path world = std::filesystem::absolute(options.input).parent_path();
  folders.push_back(world.has_parent_path() ? world.parent_path() : world);
  folders.insert(folders.end(), options.allowRead.begin(), options.allowRead.end());
  return folders;
}

}  // namespace

void addServeCommand(CLI::App& app, ServeOptions& options) {
  CLI::App* cmd = app.add_subcommand("serve",
                                     "Open a world (or a plan's or dataset's grasps) in the "
                                     "browser: move the hand, turn its DOFs, "
                                     "autograsp, plan, validate, save");
  cmd->add_option("input", options.input,
                  "World XML, a plan's JSON (plan --out) or a grasp dataset (batch's .h5)")
      ->required()
      ->check(existingFile());
  cmd->add_option("--port", options.port, "Port on 127.0.0.1 (0: any free port)")
      ->check(CLI::Range(0, 65535));
  cmd->add_option("--allow-read", options.allowRead,
                  "A folder the page may load worlds from (repeatable)");
  cmd->add_option(
      "--allow-write", options.allowWrite,
      "A folder the page may save worlds and pictures to (repeatable; none: no saving)");
  addLoadFlags(*cmd, options.load);
}

int runServe(const ServeOptions& options, std::ostream& out) {
  EditorOptions editor;
  editor.load = options.load.options();
  editor.files = lua::PathPolicy(readableFolders(options), options.allowWrite);
  EditorSession session(options.input, std::move(editor));
  ServerOptions server;
  server.port = options.port;
  if (const char* token = std::getenv("GRASPKIT_SERVE_TOKEN"); token != nullptr && *token != '\0')
    server.token = token;
  return serveEditor(session, server, out);
}

}  // namespace graspkit::cli
