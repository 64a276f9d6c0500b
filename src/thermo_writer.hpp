// The thermo output of a simulation: one row of column values per thermo step, to the
// console and to a CSV file. Owns the file and the rules for continuing one (a restarted
// run drops the rows past its checkpoint and repeats no row).
#pragma once

#include <fstream>
#include <string>
#include <vector>

namespace slender {

struct ThermoOptions {
  long every = 0;         // steps between lines, or
  double interval = 0.0;  // time between lines
  std::vector<std::string> columns{"step", "time", "ke", "pe", "etotal"};
  std::string file;
  bool append = false;  // continue an existing CSV (a restarted run)
  bool console = true;
  double progress_seconds = 5.0;
};

class ThermoWriter {
 public:
  // Writes one row of `vals` (one per column of `thermo`); `header` repeats the column
  // names on the console. The file is opened at the first row (truncated, or continued
  // when thermo.append). The values have passed the guard: they are finite.
  void write(const ThermoOptions& thermo, const std::vector<double>& vals, bool header,
             bool verbose);

 private:
  std::ofstream csv_;
  bool header_written_ = false;
  // step of the last row in the file (when its first column is "step"): a run continuing
  // where the last one ended, or a restart appending to its file, does not repeat that row
  double last_step_ = -1;
};

}  // namespace slender
