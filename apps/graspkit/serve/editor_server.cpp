#include "serve/editor_server.hpp"

#include <pthread.h>
#include <signal.h>

#include <array>
#include <atomic>
#include <chrono>
#include <fstream>
#include <mutex>
#include <thread>

#include <fmt/format.h>
#include <httplib.h>

namespace graspkit::cli {

extern const char* const kEditorScript;  // viewer/build.mjs; null when built without the viewer

namespace {

using nlohmann::json;

constexpr const char* kEditorPageStart = R"page(<!doctype html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="generator" content="graspkit serve">
<title>graspkit serve</title>
<style>
  html, body { margin: 0; height: 100%; font: 13px system-ui, sans-serif; overflow: hidden; }
  #view { display: block; position: absolute; left: 0; top: 0; right: 300px; bottom: 0;
          width: calc(100% - 300px); height: 100%; }
  #side { position: absolute; top: 0; right: 0; width: 292px; bottom: 0; overflow-y: auto;
          padding: 4px; background: #f6f6f6; border-left: 1px solid #ccc; }
  #side h3 { margin: 8px 0 4px; font-size: 13px; }
  #side label { display: block; }
  #side input[type=range] { width: 170px; vertical-align: middle; }
  #side input[type=number] { width: 72px; }
  .row { margin: 2px 0; }
  .bad { color: #b00; }
  .good { color: #070; }
  #message { min-height: 1.2em; }
  progress { width: 180px; }
  textarea { width: 280px; height: 90px; font: 11px monospace; }
</style>
</head>
<body>
<canvas id="view"></canvas>
<div id="side"></div>
<script>
)page";

constexpr const char* kEditorPageEnd = "</script>\n</body>\n</html>\n";

bool sameText(const std::string& a, const std::string& b) {
  // Compared in time that does not depend on where they differ.
  if (a.size() != b.size()) return false;
  unsigned char diff = 0;
  for (std::size_t i = 0; i < a.size(); ++i) diff |= static_cast<unsigned char>(a[i] ^ b[i]);
  return diff == 0;
}

// A token bucket shared by every connection.
class RateLimit {
 public:
  RateLimit(double rate, double burst) : rate_(rate), burst_(burst), tokens_(burst) {}
  bool take() {
    std::lock_guard lock(mutex_);
    const auto now = std::chrono::steady_clock::now();
    tokens_ =
        std::min(burst_, tokens_ + rate_ * std::chrono::duration<double>(now - last_).count());
    last_ = now;
    if (tokens_ < 1.0) return false;
    tokens_ -= 1.0;
    return true;
  }

 private:
  std::mutex mutex_;
  double rate_, burst_, tokens_;
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

void answerError(httplib::Response& res, int status, const std::string& message) {
  res.status = status;
  res.set_content(json{{"error", message}}.dump(), "application/json");
}

void secure(httplib::Response& res) {
  res.set_header("Cache-Control", "no-store");
  res.set_header("X-Content-Type-Options", "nosniff");
  res.set_header("Referrer-Policy", "no-referrer");
}

// Runs `work`, turning what it throws into the answer's status and a JSON error.
template <typename Work>
void guarded(httplib::Response& res, Work&& work) {
  try {
    work();
  } catch (const RequestError& e) {
    answerError(res, e.status(), e.what());
  } catch (const json::exception& e) {
    answerError(res, 400, fmt::format("a malformed request: {}", e.what()));
  } catch (const Error& e) {
    answerError(res, 400, e.what());
  } catch (const std::exception& e) {
    answerError(res, 500, fmt::format("internal error: {}", e.what()));
  }
}

json parseBody(const httplib::Request& req) {
  if (req.body.empty()) return json::object();
  json args = json::parse(req.body, nullptr, false);
  if (args.is_discarded()) throw RequestError(400, "the request body is not valid JSON");
  return args;
}

}  // namespace

std::string randomToken() {
  std::ifstream random("/dev/urandom", std::ios::binary);
  std::array<unsigned char, 16> bytes{};
  if (!random.read(reinterpret_cast<char*>(bytes.data()), bytes.size()))
    throw Error("cannot read /dev/urandom for the server's token");
  std::string token;
  for (unsigned char b : bytes) token += fmt::format("{:02x}", b);
  return token;
}

int serveEditor(EditorSession& session, const ServerOptions& options, std::ostream& out) {
  if (kEditorScript == nullptr)
    throw Error(
        "graspkit serve: this graspkit was built without the web page (it needs node and npm "
        "when it is built; see docs/editor.md)");
  const std::string token = options.token.empty() ? randomToken() : options.token;
  // SIGINT and SIGTERM are waited for on a thread of their own, which stops the server; the
  // server's threads, started after, inherit the mask.
  sigset_t stopSignals;
  sigemptyset(&stopSignals);
  sigaddset(&stopSignals, SIGINT);
  sigaddset(&stopSignals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stopSignals, nullptr);

  httplib::Server server;
  server.set_payload_max_length(options.maxRequestBytes);
  server.set_read_timeout(10, 0);
  server.set_tcp_nodelay(true);  // small answers go out at once, not after a delayed ACK
  RateLimit limit(options.requestsPerSecond, options.burst);
  int port = 0;
  server.set_pre_routing_handler([&](const httplib::Request& req, httplib::Response& res) {
    secure(res);
    if (req.path == "/favicon.ico") {  // browsers ask for it without the token: none
      res.status = 204;
      return httplib::Server::HandlerResponse::Handled;
    }
    // A page of another site reaching 127.0.0.1 through a name it controls (DNS rebinding)
    // sends its own host name.
    const std::string host = req.get_header_value("Host");
    if (host != fmt::format("127.0.0.1:{}", port) && host != fmt::format("localhost:{}", port)) {
      answerError(res, 403, "refused: the Host header is not this server's loopback address");
      return httplib::Server::HandlerResponse::Handled;
    }
    const std::string given = req.has_header("X-Graspkit-Token")
                                  ? req.get_header_value("X-Graspkit-Token")
                                  : req.get_param_value("token");
    if (!sameText(given, token)) {
      answerError(res, 403, "refused: no valid token (open the address graspkit serve printed)");
      return httplib::Server::HandlerResponse::Handled;
    }
    if (!limit.take()) {
      answerError(res, 429, "refused: too many requests");
      return httplib::Server::HandlerResponse::Handled;
    }
    return httplib::Server::HandlerResponse::Unhandled;
  });
  server.Get("/", [&](const httplib::Request&, httplib::Response& res) {
    res.set_header("Content-Security-Policy",
                   "default-src 'none'; script-src 'unsafe-inline'; style-src 'unsafe-inline'; "
                   "connect-src 'self'; img-src 'self' blob: data:");
    res.set_content(std::string(kEditorPageStart) + kEditorScript + kEditorPageEnd, "text/html");
  });
  server.Get("/api/scene.glb", [&](const httplib::Request&, httplib::Response& res) {
    guarded(res, [&] { res.set_content(session.sceneGltf(), "model/gltf-binary"); });
  });
  server.Post("/api/picture.png", [&](const httplib::Request& req, httplib::Response& res) {
    guarded(res, [&] { res.set_content(session.picturePng(parseBody(req)), "image/png"); });
  });
  server.Post(R"(/api/([a-z_]+))", [&](const httplib::Request& req, httplib::Response& res) {
    guarded(res, [&] {
      res.set_content(session.act(req.matches[1].str(), parseBody(req)).dump(), "application/json");
    });
  });
  server.set_error_handler([](const httplib::Request&, httplib::Response& res) {
    if (res.body.empty()) answerError(res, res.status, fmt::format("HTTP {}", res.status));
  });

  if (options.port == 0) {
    port = server.bind_to_any_port("127.0.0.1");
  } else {
    port = options.port;
    if (!server.bind_to_port("127.0.0.1", options.port)) port = -1;
  }
  if (port < 0)
    throw Error(fmt::format("graspkit serve: cannot listen on 127.0.0.1:{} (in use? try --port 0)",
                            options.port));
  std::atomic<bool> stopped{false};
  std::thread waiter([&] {
    int signal = 0;
    sigwait(&stopSignals, &signal);
    stopped = true;
    server.stop();
  });
  out << fmt::format("graspkit serve: http://127.0.0.1:{}/?token={}\n", port, token)
      << "graspkit serve: Ctrl-C stops it\n";
  out.flush();
  server.listen_after_bind();
  if (!stopped) pthread_kill(waiter.native_handle(), SIGTERM);
  waiter.join();
  return 0;
}

}  // namespace graspkit::cli
