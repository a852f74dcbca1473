#include "kestrel/budget/insn_counter.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <iostream>

#include "kestrel/budget/error.hpp"

extern char** environ;

namespace kestrel::budget {

CountResult count_instructions(const std::vector<std::string>& emulator, const std::string& plugin,
                               const std::vector<std::string>& program_args, bool quiet) {
  if (emulator.empty()) throw BudgetError("no emulator command (expected qemu-arm)");
  if (program_args.empty()) throw BudgetError("no program to run");
  char tmpl[] = "/tmp/kestrel-insns-XXXXXX";
  const int fd = mkstemp(tmpl);
  if (fd < 0) throw BudgetError("cannot create a temporary file for the plugin output");
  close(fd);
  const std::string out_file = tmpl;

  std::vector<std::string> args = emulator;
  args.push_back("-plugin");
  args.push_back(plugin + ",outfile=" + out_file);
  args.insert(args.end(), program_args.begin(), program_args.end());
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  // Quiet runs keep the program's stderr in a file, shown only when the run fails.
  char err_tmpl[] = "/tmp/kestrel-insns-err-XXXXXX";
  std::string err_file;
  if (quiet) {
    const int efd = mkstemp(err_tmpl);
    if (efd >= 0) {
      close(efd);
      err_file = err_tmpl;
      posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err_file.c_str(), O_WRONLY, 0);
    }
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  }
  const auto drop_err = [&](bool show) {
    if (err_file.empty()) return;
    if (show) {
      std::ifstream e(err_file);
      std::cerr << e.rdbuf();
    }
    std::remove(err_file.c_str());
  };
  pid_t pid = 0;
  const int rc = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) {
    drop_err(false);
    std::remove(out_file.c_str());
    throw BudgetError("cannot start " + args[0]);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
  }
  CountResult r;
  drop_err(!WIFEXITED(status) || WEXITSTATUS(status) != 0);
  if (WIFEXITED(status)) {
    r.exit_status = WEXITSTATUS(status);
  } else {
    std::remove(out_file.c_str());
    throw BudgetError(args[0] + " was killed by a signal");
  }
  std::ifstream in(out_file);
  std::string word;
  uint64_t n = 0;
  const bool ok = static_cast<bool>(in >> word >> n) && word == "insns";
  std::remove(out_file.c_str());
  if (!ok) {
    throw BudgetError("no instruction count from the plugin (" + plugin +
                      "); did qemu load it? exit status " + std::to_string(r.exit_status));
  }
  r.insns = n;
  return r;
}

double per_iteration(uint64_t count1, uint64_t n1, uint64_t count2, uint64_t n2) {
  if (n2 <= n1) throw BudgetError("the second iteration count must be larger than the first");
  if (count2 < count1) {
    throw BudgetError(
        "more iterations executed fewer instructions: the program does not run "
        "a fixed number of iterations");
  }
  return static_cast<double>(count2 - count1) / static_cast<double>(n2 - n1);
}

}  // namespace kestrel::budget
