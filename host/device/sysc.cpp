#include "voxcd/host/device/detail/sysc.h"
#include "voxcd/host/package/paths.h"

#include "voxcd/ref/address_map.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/server_protocol.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>

extern char** environ;

namespace voxcd {

namespace {

// The server: $VOXCD_SYSC_SERVER, else where the package installs it (host/package/paths.h); `name` says whose.
std::string server_path(const std::string& name) {
  const std::string why = sysc_unavailable();
  if (!why.empty()) throw DeviceError(name + ": " + why);
  return sysc_server_path();
}

class SyscDevice final : public Device {
 public:
  SyscDevice(const std::string& target, const DeviceConfig& cfg, const DeviceOptions& opt)
      : name_("sysc-" + target), cfg_(cfg) {
    cfg_.validate();
    const std::string path = server_path(name_);  // before any descriptor exists
    int sv[2];
    if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv) != 0)
      throw DeviceError(name_ + ": socketpair: " + std::strerror(errno));
    fd_ = sv[0];
    int child = sv[1];
    if (child == sysc::kServerFd) {  // dup2 onto itself would keep close-on-exec
      child = ::fcntl(sv[1], F_DUPFD_CLOEXEC, sysc::kServerFd + 1);
      ::close(sv[1]);
    }
    std::vector<std::string> args = {path, "--target", target, "--config", cfg_.to_string()};
    if (!opt.trace_path.empty()) args.insert(args.end(), {"--trace", opt.trace_path});
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    std::vector<std::string> env_store = {"SYSTEMC_DISABLE_COPYRIGHT_MESSAGE=1"};
    std::vector<char*> envp = {env_store[0].data()};
    for (char** e = environ; *e; ++e)
      if (std::strncmp(*e, "SYSTEMC_DISABLE_COPYRIGHT_MESSAGE=", 34) != 0) envp.push_back(*e);
    envp.push_back(nullptr);
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_adddup2(&fa, child, sysc::kServerFd);
    posix_spawn_file_actions_adddup2(&fa, 2, 1);  // nothing the server prints may reach our stdout
    const int rc = ::posix_spawn(&pid_, path.c_str(), &fa, nullptr, argv.data(), envp.data());
    posix_spawn_file_actions_destroy(&fa);
    ::close(child);
    if (rc != 0) {
      ::close(fd_);
      throw DeviceError(name_ + ": cannot start " + path + ": " + std::strerror(rc) +
                        " (set VOXCD_SYSC_SERVER to the voxcd_sysc_server program)");
    }
    try {
      expect_ok("starting");
    } catch (...) {
      stop();  // no destructor runs for a constructor that throws
      throw;
    }
  }

  ~SyscDevice() override { stop(); }

  std::string name() const override { return name_; }
  const DeviceConfig& config() const override { return cfg_; }
  bool models_cycles() const override { return true; }

  void load(const DeviceMemory& mem) override {
    validate_memory(cfg_, mem);
    sysc::Channel ch(fd_);
    ch.put_u64(sysc::kOpLoad);
    ch.put_u64(mem.shell.size());
    for (const ShellWord& w : mem.shell) {
      ch.put_u64(uint64_t(w.x));
      ch.put_u64(uint64_t(w.y));
      ch.put_u64(uint64_t(w.z));
    }
    ch.put_u64(mem.map.size());
    for (uint64_t w : mem.map) ch.put_u64(w);
    send(ch);
    expect_ok("loading");
    last_sim_ps_ = read_u64();
    shell_words_ = mem.shell.size();
    map_words_ = mem.map.size();
  }

  std::vector<Record> run(const std::vector<Job>& jobs) override {
    for (const Job& j : jobs) validate_job(cfg_, j, shell_words_, map_words_);
    if (jobs.empty()) return {};
    sysc::Channel ch(fd_);
    ch.put_u64(sysc::kOpRun);
    ch.put_u64(jobs.size());
    std::vector<uint8_t> buf(sysc::kJobBytes);
    for (const Job& j : jobs) {
      sysc::encode_job(j, buf.data());
      ch.put(buf.data(), buf.size());
    }
    const uint64_t before = last_sim_ps_;
    send(ch);
    expect_ok("running");
    std::vector<Record> out(read_u64());
    // All records in one read (not one read per record), and the whole answer read before any record is
    // decoded: a bad record must not leave the rest of the answer to be taken for the next one.
    std::vector<uint8_t> rb(out.size() * sysc::kRecordBytes);
    if (!rb.empty()) read_bytes(rb.data(), rb.size());
    last_sim_ps_ = read_u64();
    const uint64_t wall_ns = read_u64();
    for (size_t i = 0; i < out.size(); ++i)
      if (!sysc::decode_record(rb.data() + i * sysc::kRecordBytes, out[i]))
        throw DeviceError(name_ + ": the server sent an empty record (record " + std::to_string(i) + " of " +
                          std::to_string(out.size()) + ")");
    last_.simulated_s = double(last_sim_ps_ - before) * 1e-12;
    last_.wall_s = double(wall_ns) * 1e-9;
    return out;
  }

  SyscRunTime last_run() const { return last_; }

 private:
  void stop() {
    ::close(fd_);  // the server ends at the end of its input
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
  }
  void send(sysc::Channel& ch) {
    try {
      ch.flush();
    } catch (const std::exception&) {
      throw DeviceError(name_ + ": the SystemC server has ended");
    }
  }
  void read_bytes(void* p, size_t n) {
    try {
      sysc::Channel ch(fd_);
      if (!ch.get(p, n)) throw std::runtime_error("end of stream");
    } catch (const std::exception&) {
      throw DeviceError(name_ + ": the SystemC server ended without an answer (its messages are above)");
    }
  }
  uint64_t read_u64() {
    uint8_t b[8];
    read_bytes(b, 8);
    return sysc::get_le(b, 8);
  }
  void expect_ok(const char* what) {
    if (read_u64() == 0) return;
    std::string msg(read_u64(), '\0');
    if (!msg.empty()) read_bytes(&msg[0], msg.size());
    throw DeviceError(name_ + ": " + what + ": " + msg);
  }

  std::string name_;
  DeviceConfig cfg_;
  int fd_ = -1;
  pid_t pid_ = -1;
  uint64_t shell_words_ = 0, map_words_ = 0;
  uint64_t last_sim_ps_ = 0;
  SyscRunTime last_;
};

}  // namespace

std::string sysc_unavailable() {
  if (std::getenv("VOXCD_SYSC_SERVER")) return "";  // the caller's choice: starting it says what is wrong with it
#if !VOXCD_DEVICE_MODELS
  return "this build was configured without the device models (-DVOXCD_DEVICE_MODELS=OFF)";
#else
  try {
    sysc_server_path();
    return "";
  } catch (const std::runtime_error&) {
    const std::string cmd = models_build_command();
    if (!cmd.empty()) return "the SystemC platform server is not built (build it with `" + cmd + "`)";
    return "this installation has no SystemC platform server (build it with `cmake --build BUILD --target "
           "voxcd_models` before `cmake --install BUILD`)";
  }
#endif
}

bool have_sysc() { return sysc_unavailable().empty(); }

std::unique_ptr<Device> make_sysc_device(const std::string& target, const DeviceConfig& cfg, const DeviceOptions& opt) {
  if (target != "rtl" && target != "tlm") throw DeviceError("sysc: no target '" + target + "' (rtl or tlm)");
  return std::make_unique<SyscDevice>(target, cfg, opt);
}

SyscRunTime sysc_last_run(const Device& dev) {
  if (const auto* s = dynamic_cast<const SyscDevice*>(&dev)) return s->last_run();
  return {};
}

}  // namespace voxcd
