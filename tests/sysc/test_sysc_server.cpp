// The host's sysc backends (host/device/sysc.cpp) when their server process fails: missing, ended at any point,
// started with bad arguments, or answering with an empty record; and an unknown target. Each must be a DeviceError
// that says what happened, never a hang or a crash, and a failed start leaves no descriptor or child behind.
// The misbehaving servers are tests/sysc/fake_sysc_server.cpp, chosen by VOXCD_SYSC_SERVER; no test here elaborates
// SystemC in its own process.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <utility>

#include "voxcd/host/device/device.h"
#include "voxcd/host/device/detail/sysc.h"
#include "voxcd/ref/pipeline.h"
#include "tests/error_text.h"

namespace voxcd {
namespace {

// The text of the DeviceError fn throws (tests/error_text.h).
template <class Fn>
std::string device_error(Fn&& fn) {
  return test::error_text<DeviceError>(std::forward<Fn>(fn));
}

namespace fs = std::filesystem;

// Sets an environment variable for the life of the object.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    ::setenv(name, value.c_str(), 1);
  }
  ~ScopedEnv() {
    if (old_)
      ::setenv(name_, old_->c_str(), 1);
    else
      ::unsetenv(name_);
  }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

// A hang is a failure: the process ends with SIGALRM long before ctest's own timeout.
class Watchdog {
 public:
  Watchdog() { ::alarm(60); }
  ~Watchdog() { ::alarm(0); }
};

size_t open_descriptors() {
  size_t n = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator("/proc/self/fd")) ++n;
  return n;
}

// True when this process has no child left, running or unreaped.
bool no_children() {
  errno = 0;
  return ::waitpid(-1, nullptr, WNOHANG) == -1 && errno == ECHILD;
}

DeviceMemory small_memory() {
  DeviceMemory m;
  m.shell.resize(1);
  m.map.assign(1, 0x5555555555555555ull);
  return m;
}

Job small_job(uint32_t tag) {
  Job j;
  j.tag = tag;
  j.shell_count = 1;
  return j;
}

const std::string kEnded = "sysc-tlm: the SystemC server has ended";
const std::string kNoAnswer = "sysc-tlm: the SystemC server ended without an answer (its messages are above)";

TEST(SyscServer, MissingOrUnrunnableServerProgram) {
  Watchdog w;
  const size_t fds = open_descriptors();
  {
    ScopedEnv env("VOXCD_SYSC_SERVER", "/nonexistent/voxcd_sysc_server");
    EXPECT_EQ(device_error([] { make_device("sysc-tlm", DeviceConfig{}); }),
              "sysc-tlm: cannot start /nonexistent/voxcd_sysc_server: No such file or directory (set "
              "VOXCD_SYSC_SERVER to the voxcd_sysc_server program)");
    EXPECT_EQ(device_error([] { make_device("sysc-rtl", DeviceConfig{}); }),
              "sysc-rtl: cannot start /nonexistent/voxcd_sysc_server: No such file or directory (set "
              "VOXCD_SYSC_SERVER to the voxcd_sysc_server program)");
  }
  const fs::path plain = fs::temp_directory_path() / ("voxcd_not_a_program_" + std::to_string(::getpid()));
  std::ofstream(plain) << "not a program\n";
  fs::permissions(plain, fs::perms::owner_read | fs::perms::owner_write);
  {
    ScopedEnv env("VOXCD_SYSC_SERVER", plain.string());
    EXPECT_EQ(device_error([] { make_device("sysc-tlm", DeviceConfig{}); }),
              "sysc-tlm: cannot start " + plain.string() +
                  ": Permission denied (set VOXCD_SYSC_SERVER to the voxcd_sysc_server program)");
  }
  fs::remove(plain);
  EXPECT_EQ(open_descriptors(), fds);
  EXPECT_TRUE(no_children());
}

TEST(SyscServer, UnknownTargetIsNamed) {
  EXPECT_EQ(device_error([] { make_sysc_device("gpu", DeviceConfig{}, {}); }), "sysc: no target 'gpu' (rtl or tlm)");
  EXPECT_EQ(device_error([] { make_sysc_device("", DeviceConfig{}, {}); }), "sysc: no target '' (rtl or tlm)");
  EXPECT_TRUE(no_children());
}

// The real server, run by hand with bad arguments: its message and usage on stderr, exit status 2.
TEST(SyscServer, BadArgumentsGiveTheServersUsageAndStatusTwo) {
  ::setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "1", 1);
  const std::string server = VOXCD_SYSC_SERVER_BIN;
  const std::string usage = "usage: voxcd_sysc_server --target rtl|tlm --config PAIRS [--trace FILE]";
  const std::string cfg = "'" + DeviceConfig{}.to_string() + "'";
  const struct {
    std::string args, message;
  } cases[] = {
      {"--target nosuch --config " + cfg, "voxcd_sysc_server: unknown target nosuch"},
      {"--config " + cfg, "voxcd_sysc_server: --target is required"},
      {"--target", "voxcd_sysc_server: missing value after --target"},
      {"--target tlm --config 'MEMW 48'",
       "voxcd_sysc_server: --config: invalid device configuration: MEMW = 48 is not a power of two"},
      {"--target tlm --frob 1", "voxcd_sysc_server: unknown option --frob"},
  };
  for (const auto& c : cases) {
    FILE* p = ::popen((server + " " + c.args + " 2>&1 </dev/null").c_str(), "r");
    ASSERT_NE(p, nullptr);
    std::string out;
    char buf[512];
    while (size_t n = std::fread(buf, 1, sizeof buf, p)) out.append(buf, n);
    const int status = ::pclose(p);
    ASSERT_TRUE(WIFEXITED(status)) << c.args;
    EXPECT_EQ(WEXITSTATUS(status), 2) << c.args;
    EXPECT_EQ(out, c.message + "\n" + usage + "\n") << c.args;
  }
}

// The same through a backend: a server that ends before it is ready is an error when the device is made, and the
// server's own message is on stderr above it. Nothing is left open.
TEST(SyscServer, ServerThatEndsAtStartIsAnErrorWithItsMessageAbove) {
  Watchdog w;
  ::setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "1", 1);
  ScopedEnv server("VOXCD_SYSC_SERVER", VOXCD_FAKE_SERVER);
  ScopedEnv mode("VOXCD_FAKE_SERVER", "bad-target");
  const size_t fds = open_descriptors();
  // Capture what the server prints (the backend gives it our stderr).
  const fs::path log = fs::temp_directory_path() / ("voxcd_server_log_" + std::to_string(::getpid()));
  std::fflush(stderr);
  const int saved = ::dup(2);
  const int f = ::open(log.c_str(), O_CREAT | O_TRUNC | O_WRONLY, 0600);
  ASSERT_GE(f, 0);
  ::dup2(f, 2);
  ::close(f);
  const std::string e = device_error([] { make_device("sysc-tlm", DeviceConfig{}); });
  ::dup2(saved, 2);
  ::close(saved);
  EXPECT_EQ(e, kNoAnswer);
  std::stringstream printed;
  printed << std::ifstream(log).rdbuf();
  fs::remove(log);
  EXPECT_NE(printed.str().find("voxcd_sysc_server: unknown target nosuch"), std::string::npos) << printed.str();
  EXPECT_EQ(open_descriptors(), fds);
  EXPECT_TRUE(no_children());
}

// A server that ends after it is ready: a request that is sent whole is an error when the answer does not come; a
// request that cannot be sent (larger than the socket holds) is an error when sending; every later request on the
// device is an error when sending. The caller's records stay as they were.
TEST(SyscServer, ServerThatEndsMidRunIsAnError) {
  Watchdog w;
  ScopedEnv server("VOXCD_SYSC_SERVER", VOXCD_FAKE_SERVER);
  {
    ScopedEnv mode("VOXCD_FAKE_SERVER", "end-on-run");
    auto dev = make_device("sysc-tlm", DeviceConfig{});
    dev->load(small_memory());
    std::vector<Record> out = {Record::done(9, 0, 1)};
    EXPECT_EQ(device_error([&] { dev->run_into({small_job(1)}, out); }), kNoAnswer);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].tag, 9u);
    EXPECT_EQ(device_error([&] { dev->run_into({small_job(2)}, out); }), kEnded);
    EXPECT_EQ(device_error([&] { dev->load(small_memory()); }), kEnded);
    ASSERT_EQ(out.size(), 1u);
  }
  {
    ScopedEnv mode("VOXCD_FAKE_SERVER", "end-at-once");
    auto dev = make_device("sysc-tlm", DeviceConfig{});
    DeviceMemory big;  // 3.5 MB of request
    big.shell.resize(size_t{1} << 16);
    big.map.resize(size_t{1} << 18);
    EXPECT_EQ(device_error([&] { dev->load(big); }), kEnded);
    EXPECT_EQ(device_error([&] { dev->load(small_memory()); }), kEnded);
  }
  EXPECT_TRUE(no_children());
}

// A server that sends an empty record (kind 0) where a record belongs: an error naming the record, and the device
// stays in step with the server, so the next run gives its records.
TEST(SyscServer, EmptyRecordIsAnErrorNamingItAndTheConnectionStaysInStep) {
  Watchdog w;
  ScopedEnv server("VOXCD_SYSC_SERVER", VOXCD_FAKE_SERVER);
  ScopedEnv mode("VOXCD_FAKE_SERVER", "empty-record");
  auto dev = make_device("sysc-tlm", DeviceConfig{});
  dev->load(small_memory());
  std::vector<Record> out = {Record::done(9, 0, 1)};
  EXPECT_EQ(device_error([&] { dev->run_into({small_job(1), small_job(2)}, out); }),
            "sysc-tlm: the server sent an empty record (record 2 of 3)");
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].tag, 9u);
  const std::vector<Record> next = dev->run({small_job(3)});
  ASSERT_EQ(next.size(), 1u);
  EXPECT_EQ(next[0].kind, Record::Done);
  EXPECT_EQ(next[0].tag, 3u);
}

}  // namespace
}  // namespace voxcd
