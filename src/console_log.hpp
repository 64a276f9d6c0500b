// A copy of the console in a file (the role of LAMMPS's log.lammps): everything the
// process writes to stdout and stderr (the run's lines, Lua's print, the error line)
// reaches the terminal as before and the log file as well, in the order it was written.
#pragma once

#include <string>
#include <thread>

namespace slender {

class ConsoleLog {
 public:
  // Starts copying; throws std::runtime_error naming the file when it cannot be created.
  explicit ConsoleLog(const std::string& path);
  // Flushes the streams, gives stdout and stderr back and writes what is left to the file.
  ~ConsoleLog();
  // Writes a line to the file only (the command line and the date at the top).
  void note(const std::string& line);
  ConsoleLog(const ConsoleLog&) = delete;
  ConsoleLog& operator=(const ConsoleLog&) = delete;

 private:
  void copy_loop();
  int file_ = -1;              // the log file
  int console_[2] = {-1, -1};  // the original stdout and stderr
  int read_[2] = {-1, -1};     // read ends of the pipes now behind fds 1 and 2
  int wake_[2] = {-1, -1};     // the destructor's "finish" signal to the copier
  std::thread copier_;
};

}  // namespace slender
