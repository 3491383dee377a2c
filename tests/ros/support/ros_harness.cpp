// SPDX-License-Identifier: BSD-3-Clause
#include "tests/ros/support/ros_harness.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <ros/ros.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace lmk::test {

ChildProcess::ChildProcess(std::vector<std::string> argv, std::string log_path)
    : log_path_(std::move(log_path)) {
  std::vector<char*> args;
  for (std::string& a : argv) args.push_back(a.data());
  args.push_back(nullptr);
  pid_ = fork();
  if (pid_ < 0) throw std::runtime_error("fork failed");
  if (pid_ == 0) {
    const int fd = open(log_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      dup2(fd, STDOUT_FILENO);
      dup2(fd, STDERR_FILENO);
    }
    setpgid(0, 0);  // its own group, so that stop() reaches anything it starts
    execvp(args[0], args.data());
    _exit(127);
  }
  setpgid(pid_, pid_);  // as the child does: whichever runs first, the group exists
}

ChildProcess::~ChildProcess() { stop(); }

bool ChildProcess::running() { return wait(0.0) == -1; }

int ChildProcess::wait(double seconds) {
  if (pid_ < 0) return status_;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (true) {
    int status = 0;
    const pid_t r = waitpid(pid_, &status, WNOHANG);
    if (r == pid_) {
      status_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      pid_ = -1;
      return status_;
    }
    if (std::chrono::steady_clock::now() >= deadline) return -1;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

void ChildProcess::stop() {
  if (pid_ < 0) return;
  kill(-pid_, SIGTERM);
  if (wait(5.0) == -1) {
    kill(-pid_, SIGKILL);
    wait(5.0);
  }
}

std::string ChildProcess::log() const {
  std::ifstream in(log_path_);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::pair<int, std::string> run_to_end(std::vector<std::string> argv, const std::string& log_path,
                                       double seconds) {
  ChildProcess process(std::move(argv), log_path);
  const int code = process.wait(seconds);
  return {code, process.log()};
}

int free_port() {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  addr.sin_port = 0;
  socklen_t len = sizeof addr;
  if (fd < 0 || bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 ||
      getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len) != 0) {
    if (fd >= 0) close(fd);
    throw std::runtime_error("no free port");
  }
  close(fd);
  return ntohs(addr.sin_port);
}

RosMaster::RosMaster() {
  char pattern[] = "/tmp/lmk-ros-XXXXXX";
  if (!mkdtemp(pattern)) throw std::runtime_error("cannot make a ROS_HOME");
  home_ = pattern;
  setenv("ROS_HOME", home_.c_str(), 1);
  setenv("ROS_LOG_DIR", (home_ + "/log").c_str(), 1);
  setenv("ROS_IP", "127.0.0.1", 1);  // loopback only: the tests never reach other machines
  unsetenv("ROS_HOSTNAME");
  // A port can be taken between free_port() and the master's bind: try a few.
  for (int attempt = 0; attempt < 5 && !process_; ++attempt) {
    port_ = free_port();
    auto* process = new ChildProcess(
        {"rosmaster", "--core", "-p", std::to_string(port_), "-w", "3"}, home_ + "/rosmaster.log");
    setenv("ROS_MASTER_URI", uri().c_str(), 1);
    // Up when something accepts on the port; gone if the process ended.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    bool up = false;
    while (!up && process->running() && std::chrono::steady_clock::now() < deadline) {
      const int fd = socket(AF_INET, SOCK_STREAM, 0);
      sockaddr_in addr{};
      addr.sin_family = AF_INET;
      addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
      addr.sin_port = htons(static_cast<std::uint16_t>(port_));
      up = connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0;
      close(fd);
      if (!up) std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    if (up) {
      process_ = process;
    } else {
      delete process;
    }
  }
  if (!process_) throw std::runtime_error("rosmaster did not start (see " + home_ + ")");
}

RosMaster::~RosMaster() {
  delete process_;  // stops it
  std::error_code ec;
  std::filesystem::remove_all(home_, ec);
}

std::string RosMaster::uri() const { return "http://127.0.0.1:" + std::to_string(port_) + "/"; }

namespace {

class RosEnvironment : public ::testing::Environment {
 public:
  explicit RosEnvironment(std::string name) : name_(std::move(name)) {}
  void SetUp() override {
    master_ = std::make_unique<RosMaster>();
    int argc = 0;
    ::ros::init(argc, nullptr, name_, ::ros::init_options::NoSigintHandler);
    ASSERT_TRUE(::ros::master::check()) << "no rosmaster at " << master_->uri();
    spinner_ = std::make_unique<::ros::AsyncSpinner>(2);
    spinner_->start();
  }
  void TearDown() override {
    spinner_.reset();
    ::ros::shutdown();
    master_.reset();
  }

 private:
  std::string name_;
  std::unique_ptr<RosMaster> master_;
  std::unique_ptr<::ros::AsyncSpinner> spinner_;
};

}  // namespace

void use_ros_master(const std::string& node_name) {
  ::testing::AddGlobalTestEnvironment(new RosEnvironment(node_name));
}

}  // namespace lmk::test
