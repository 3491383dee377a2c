// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Real ROS in lmk's tests (docs/ros.md, "Tests"): a rosmaster of the test's own on a free port,
// so that two runs never collide, and child processes (lmk_node, the lmk CLI) that the test starts
// and always stops, by pid.

#include <sys/types.h>

#include <string>
#include <utility>
#include <vector>

namespace lmk::test {

/// A child process with its output in a log file; terminated (SIGTERM, then SIGKILL after 5 s) and
/// reaped when destroyed, whatever happened to the test.
class ChildProcess {
 public:
  ChildProcess(std::vector<std::string> argv, std::string log_path);
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  pid_t pid() const { return pid_; }
  bool running();
  /// Waits up to `seconds` for the process to end; its exit code, or -1 if it is still running
  /// (then it keeps running), or 128 + the signal that ended it.
  int wait(double seconds);
  void stop();
  /// The output so far.
  std::string log() const;

 private:
  pid_t pid_ = -1;
  int status_ = -1;
  std::string log_path_;
};

/// Runs `argv` to its end (at most `seconds`; then it is stopped): its exit code and output.
std::pair<int, std::string> run_to_end(std::vector<std::string> argv, const std::string& log_path,
                                       double seconds = 300.0);

/// A rosmaster on a free port, with ROS_HOME and the logs in a directory of its own.
/// ROS_MASTER_URI and ROS_HOME are set for this process and the children it starts.
class RosMaster {
 public:
  RosMaster();
  ~RosMaster();
  RosMaster(const RosMaster&) = delete;
  RosMaster& operator=(const RosMaster&) = delete;

  int port() const { return port_; }
  std::string uri() const;
  const std::string& home() const { return home_; }

 private:
  int port_ = 0;
  std::string home_;
  ChildProcess* process_ = nullptr;
};

/// A TCP port nothing listens on now (the kernel's pick).
int free_port();

/// Installs a gtest environment that starts a RosMaster, initialises this process as a ROS node
/// named `node_name` and spins it on two threads, for every test of the binary; stopped at exit.
void use_ros_master(const std::string& node_name);

}  // namespace lmk::test
