// readInChild (io/dataset/contained_read.hpp): a reader run in a child process returns its bytes,
// its located errors arrive whole, and a crash, a runaway or an exhausted memory ends the child
// only.

#include <gtest/gtest.h>

#include <csignal>
#include <string>
#include <thread>
#include <vector>

#include "graspkit/base/error.hpp"
#include "io/dataset/contained_read.hpp"

namespace graspkit {
namespace {

using namespace std::chrono_literals;

constexpr std::size_t kMemory = std::size_t{1} << 30;

std::string errorOf(const std::function<std::string()>& read, std::chrono::seconds timeout = 10s) {
  try {
    readInChild(read, "data.h5", timeout, kMemory);
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error";
  return "";
}

TEST(ContainedRead, BytesComeBackWhole) {
  std::string bytes(300'000, '\0');  // more than a pipe holds, with NULs in it
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>(i * 7);
  EXPECT_EQ(readInChild([&] { return bytes; }, "data.h5", 10s, kMemory), bytes);
}

TEST(ContainedRead, ALocatedErrorArrivesWithItsLocation) {
  try {
    readInChild(
        []() -> std::string {
          throw Error(SourceLocation{"data.h5", 12, "grasps"}, "is missing");
        },
        "data.h5", 10s, kMemory);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.where().file, "data.h5");
    EXPECT_EQ(e.where().line, 12);
    EXPECT_EQ(e.where().element, "grasps");
    EXPECT_EQ(e.message(), "is missing");
  }
}

TEST(ContainedRead, ACrashEndsTheChildOnly) {
  const std::string message = errorOf([]() -> std::string {
    std::raise(SIGSEGV);
    return "";
  });
  EXPECT_NE(message.find("data.h5"), std::string::npos) << message;
  EXPECT_NE(message.find("crashed"), std::string::npos) << message;
}

TEST(ContainedRead, ARunawayIsStopped) {
  const std::string message = errorOf(
      []() -> std::string {
        for (;;) std::this_thread::sleep_for(1s);
      },
      1s);
  EXPECT_NE(message.find("longer than 1 s"), std::string::npos) << message;
}

}  // namespace
}  // namespace graspkit
