#include "thermo_writer.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>

#include "file_check.hpp"
#include "params.hpp"

namespace slender {

void ThermoWriter::write(const ThermoOptions& thermo, const std::vector<double>& vals, bool header,
                         bool verbose) {
  const bool by_step = !thermo.columns.empty() && thermo.columns[0] == "step";
  if (!thermo.file.empty()) {
    if (!csv_.is_open()) {
      bool has_content = false;
      if (thermo.append) {
        std::vector<std::string> lines;
        {
          std::ifstream old(thermo.file);
          std::string line;
          while (std::getline(old, line))
            if (!line.empty()) lines.push_back(line);
        }
        has_content = !lines.empty();
        if (has_content && by_step) {
          auto step_of = [](const std::string& row, double* out) {
            if (row.rfind("step", 0) == 0) return false;  // the header
            try {
              *out = std::stod(row.substr(0, row.find(',')));
              return true;
            } catch (const std::exception&) {
              return false;
            }
          };
          // A restart from a checkpoint (step > 0) redoes the steps the interrupted run
          // went on to after it: drop their rows, so the file stays one row per step, in
          // order. A new run from step 0 appends below the old one and drops nothing.
          // The row of the checkpoint's own step stays: it was written from the same
          // state, with the per-step counts (contacts) that a restart has not yet made.
          size_t keep = lines.size();
          double st = 0.0;
          while (vals[0] > 0 && keep > 0 && step_of(lines[keep - 1], &st) && st > vals[0]) --keep;
          if (keep < lines.size()) {
            const std::string tmp = thermo.file + ".tmp";
            {
              std::ofstream out(tmp, std::ios::out | std::ios::trunc);
              for (size_t i = 0; i < keep; ++i) out << lines[i] << "\n";
              if (!out) throw InputError("cannot rewrite thermo file '" + thermo.file + "'");
            }
            if (std::rename(tmp.c_str(), thermo.file.c_str()) != 0)
              throw InputError("cannot replace thermo file '" + thermo.file + "'");
            if (verbose)
              std::printf(
                  "thermo: dropped %zu rows of %s after step %.0f (written after the "
                  "checkpoint this run continues from; they are redone)\n",
                  lines.size() - keep, thermo.file.c_str(), vals[0]);
            lines.resize(keep);
          }
          has_content = !lines.empty();
          if (!lines.empty() && !step_of(lines.back(), &last_step_)) last_step_ = -1;
        }
      }
      csv_.open(thermo.file,
                thermo.append ? std::ios::out | std::ios::app : std::ios::out | std::ios::trunc);
      if (!csv_) {
        const std::string why = why_not_writable(thermo.file);
        throw InputError(
            "cannot open thermo file '" + thermo.file + "'" +
            (why.empty() ? std::string(" (") + std::strerror(errno) + ")" : ": " + why));
      }
      // appending under an existing header keeps one header per file
      header_written_ = has_content;
    }
  }
  if (!thermo.file.empty() && !(by_step && vals[0] == last_step_)) {
    if (!header_written_) {
      for (size_t i = 0; i < thermo.columns.size(); ++i)
        csv_ << (i ? "," : "") << thermo.columns[i];
      csv_ << "\n";
      header_written_ = true;
    }
    csv_.precision(12);
    for (size_t i = 0; i < vals.size(); ++i) {
      // the guard runs before thermo, so values here are finite
      csv_ << (i ? "," : "") << vals[i];
    }
    csv_ << "\n";
    csv_.flush();
    if (by_step) last_step_ = vals[0];
  }
  if (thermo.console && verbose) {
    if (header) {
      for (auto& c : thermo.columns) std::printf("%14s ", c.c_str());
      std::printf("\n");
    }
    for (double v : vals) std::printf("%14.7g ", v);
    std::printf("\n");
    std::fflush(stdout);
  }
}

}  // namespace slender
