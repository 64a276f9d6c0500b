#include "console_log.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace slender {

namespace {
void write_all(int fd, const char* p, ssize_t n) {
  while (n > 0) {
    const ssize_t w = ::write(fd, p, static_cast<size_t>(n));
    if (w < 0) {
      if (errno == EINTR) continue;
      return;  // a closed terminal or a full disk must not stop the run
    }
    p += w;
    n -= w;
  }
}
void close_on_exec(int fd) {
  ::fcntl(fd, F_SETFD, FD_CLOEXEC);
}
}  // namespace

ConsoleLog::ConsoleLog(const std::string& path) {
  file_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (file_ < 0)
    throw std::runtime_error("cannot create log file '" + path + "': " + std::strerror(errno));
  std::fflush(stdout);
  std::fflush(stderr);
  int out[2], err[2];
  if (::pipe(out) != 0 || ::pipe(err) != 0 || ::pipe(wake_) != 0)
    throw std::runtime_error(std::string("log file: no pipe: ") + std::strerror(errno));
  console_[0] = ::dup(STDOUT_FILENO);
  console_[1] = ::dup(STDERR_FILENO);
  ::dup2(out[1], STDOUT_FILENO);
  ::dup2(err[1], STDERR_FILENO);
  ::close(out[1]);
  ::close(err[1]);
  read_[0] = out[0];
  read_[1] = err[0];
  for (int fd : {console_[0], console_[1], read_[0], read_[1], wake_[0], wake_[1]})
    close_on_exec(fd);  // a program the deck starts writes through fds 1 and 2 only
  // through a pipe stdout would be fully buffered: keep the terminal's line by line
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  // signals (SIGINT, SIGTERM: the run's clean stop) go to the run's thread, not the copier
  sigset_t all, old;
  sigfillset(&all);
  pthread_sigmask(SIG_BLOCK, &all, &old);
  copier_ = std::thread([this] { copy_loop(); });
  pthread_sigmask(SIG_SETMASK, &old, nullptr);
}

void ConsoleLog::note(const std::string& line) {
  std::fflush(stdout);
  std::fflush(stderr);
  const std::string l = line + "\n";
  write_all(file_, l.data(), static_cast<ssize_t>(l.size()));
}

void ConsoleLog::copy_loop() {
  char buf[65536];
  bool open[2] = {true, true}, finishing = false;
  while (open[0] || open[1]) {
    pollfd p[3] = {{read_[0], POLLIN, 0}, {read_[1], POLLIN, 0}, {wake_[0], POLLIN, 0}};
    if (!open[0]) p[0].fd = -1;
    if (!open[1]) p[1].fd = -1;
    // after the wake-up: drain what is buffered, never wait (a program the deck started
    // in the background may still hold the pipes)
    const int r = ::poll(p, 3, finishing ? 0 : -1);
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) break;
    if (p[2].revents) finishing = true;
    for (int k = 0; k < 2; ++k) {
      if (!open[k] || !(p[k].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      const ssize_t n = ::read(read_[k], buf, sizeof buf);
      if (n <= 0) {
        if (n < 0 && errno == EINTR) continue;
        open[k] = false;
        continue;
      }
      write_all(console_[k], buf, n);
      write_all(file_, buf, n);
    }
  }
}

ConsoleLog::~ConsoleLog() {
  std::fflush(stdout);
  std::fflush(stderr);
  // fds 1 and 2 back to the terminal: the pipes' write ends close, the copier sees their end
  ::dup2(console_[0], STDOUT_FILENO);
  ::dup2(console_[1], STDERR_FILENO);
  const char c = 0;
  write_all(wake_[1], &c, 1);
  if (copier_.joinable()) copier_.join();
  for (int fd : {console_[0], console_[1], read_[0], read_[1], wake_[0], wake_[1], file_})
    if (fd >= 0) ::close(fd);
}

}  // namespace slender
