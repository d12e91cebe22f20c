// Latency of graspkit serve's JSON API as the page sees it: a real `graspkit serve` on GraspIt!'s
// plannerMug, requests over HTTP on loopback (cpp-httplib's client), one at a time. The goal
// (docs/editor.md) is an answer under 20 ms for an action that moves the hand. The hand starts on
// grasp 1 of a short plan (the Barrett closed on the mug), so each move finds contacts and
// measures the grasp; "preview" is what a drag sends while it moves, "measured" its last request.
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <regex>
#include <stdexcept>
#include <string>
#include <thread>

#include <benchmark/benchmark.h>
#include <httplib.h>
#include <nlohmann/json.hpp>

namespace {

using nlohmann::json;

class Server {
 public:
  Server() {
    const std::string world =
        std::string(GRASPKIT_SHARED_DEFAULT) + "/graspit-data/worlds/plannerMug.xml";
    int out[2];
    if (pipe(out) != 0) throw std::runtime_error("pipe");
    pid_ = fork();
    if (pid_ == 0) {
      prctl(PR_SET_PDEATHSIG, SIGTERM);  // the server goes with the bench, however it ends
      dup2(out[1], STDOUT_FILENO);
      close(out[0]);
      execl(GRASPKIT_PROGRAM, GRASPKIT_PROGRAM, "-q", "serve", world.c_str(), "--port", "0",
            static_cast<char*>(nullptr));
      _exit(127);
    }
    close(out[1]);
    std::string text;
    char buffer[256];
    std::smatch match;
    const std::regex address(R"(127\.0\.0\.1:(\d+)/\?token=([0-9a-f]+))");
    while (!std::regex_search(text, match, address)) {
      const ssize_t n = read(out[0], buffer, sizeof buffer);
      if (n <= 0) throw std::runtime_error("graspkit serve printed no address");
      text.append(buffer, static_cast<std::size_t>(n));
    }
    close(out[0]);
    client_ = std::make_unique<httplib::Client>("127.0.0.1", std::stoi(match[1].str()));
    client_->set_default_headers({{"X-Graspkit-Token", match[2].str()}});
    client_->set_keep_alive(true);
    client_->set_tcp_nodelay(true);
  }
  ~Server() {
    client_.reset();
    kill(pid_, SIGTERM);
    waitpid(pid_, nullptr, 0);
  }

  json act(const std::string& action, const json& args = json::object()) {
    const auto response = client_->Post("/api/" + action, args.dump(), "application/json");
    if (!response) throw std::runtime_error("no answer to " + action);
    json answer = json::parse(response->body);
    if (response->status != 200)
      throw std::runtime_error(action + ": " + answer.value("error", ""));
    return answer;
  }

 private:
  pid_t pid_ = -1;
  std::unique_ptr<httplib::Client> client_;
};

// One server for every benchmark, the hand on the plan's best grasp.
Server& server() {
  static Server instance;
  static const bool ready = [] {
    instance.act("plan", {{"steps", 1500}, {"seed", 3}, {"top", 3}});
    while (instance.act("plan_status")["running"].get<bool>())
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    instance.act("show_grasp", {{"index", 0}});
    return true;
  }();
  (void)ready;
  return instance;
}

// Moves the hand 1 mm back and forth along x from the grasp (contacts change little).
void moveHand(benchmark::State& state, bool preview) {
  Server& s = server();
  const json pose = s.act("state")["hand"]["pose"];
  json moved = pose;
  moved["translation"][0] = pose["translation"][0].get<double>() - 1.0;
  int contacts = 0;
  bool forward = false;
  for (auto _ : state) {
    forward = !forward;
    json args = forward ? moved : pose;
    args["preview"] = preview;
    args["group"] = "bench";
    contacts = static_cast<int>(s.act("pose", args)["contacts"].size());
  }
  state.counters["contacts"] = contacts;
}

void BM_MoveHandPreview(benchmark::State& state) {
  moveHand(state, true);
}
void BM_MoveHandMeasured(benchmark::State& state) {
  moveHand(state, false);
}

// A DOF slider's drag: finger 1 opening and closing by 0.01 rad.
void BM_DofSliderPreview(benchmark::State& state) {
  Server& s = server();
  const json now = s.act("state");
  json dofs = json::array();
  for (const json& d : now["hand"]["dofs"]) dofs.push_back(d["value"]);
  json moved = dofs;
  moved[1] = dofs[1].get<double>() - 0.01;
  bool forward = false;
  for (auto _ : state) {
    forward = !forward;
    s.act("dofs", {{"values", forward ? moved : dofs}, {"preview", true}, {"group", "bench"}});
  }
}

void BM_State(benchmark::State& state) {
  Server& s = server();
  for (auto _ : state) benchmark::DoNotOptimize(s.act("state"));
}

BENCHMARK(BM_MoveHandPreview)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_MoveHandMeasured)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_DofSliderPreview)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_State)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
