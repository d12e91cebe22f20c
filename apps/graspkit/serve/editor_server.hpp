#pragma once
// The HTTP side of `graspkit serve` (cpp-httplib): the page, the scene and one POST per action of
// the session's JSON API, on 127.0.0.1 only. Every request must carry the token the server
// printed at start (the page's URL has it); requests are limited in size and rate.

#include <cstddef>
#include <ostream>
#include <string>

#include "serve/editor_session.hpp"

namespace graspkit::cli {

struct ServerOptions {
  int port = 8765;                        // 0: any free port (the printed address says which)
  std::string token;                      // empty: a random one
  std::size_t maxRequestBytes = 1 << 20;  // larger bodies are refused (413)
  double requestsPerSecond = 1000.0;      // sustained; more are refused (429)
  double burst = 1000.0;                  // requests allowed at once before the rate applies
};

// 128 random bits from the operating system, as 32 hex digits.
std::string randomToken();

// Serves `session` until SIGINT or SIGTERM. Prints "graspkit serve: http://127.0.0.1:PORT/?token=T"
// on `out` once it listens. Throws graspkit::Error when the port cannot be bound.
int serveEditor(EditorSession& session, const ServerOptions& options, std::ostream& out);

}  // namespace graspkit::cli
