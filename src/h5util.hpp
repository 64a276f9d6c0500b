// Small RAII helpers over the HDF5 C API, shared by checkpoints and dumps.
#pragma once
#ifdef SLENDER_HAVE_HDF5

#include <hdf5.h>

#include <cstdint>
#include <string>
#include <vector>

namespace slender::h5 {

// Owns one HDF5 identifier and closes it with the right function.
class Handle {
 public:
  Handle() = default;
  Handle(hid_t id, herr_t (*closer)(hid_t)) : id_(id), close_(closer) {}
  Handle(Handle&& o) noexcept : id_(o.id_), close_(o.close_) { o.id_ = -1; }
  Handle& operator=(Handle&& o) noexcept {
    reset();
    id_ = o.id_;
    close_ = o.close_;
    o.id_ = -1;
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { reset(); }
  void reset() {
    if (id_ >= 0 && close_) close_(id_);
    id_ = -1;
  }
  hid_t get() const { return id_; }
  operator hid_t() const { return id_; }
  bool valid() const { return id_ >= 0; }

 private:
  hid_t id_ = -1;
  herr_t (*close_)(hid_t) = nullptr;
};

Handle create_file(const std::string& path);  // truncates
Handle open_file(const std::string& path, bool writable);
Handle create_group(hid_t parent, const std::string& name);
Handle open_group(hid_t parent, const std::string& name);
bool exists(hid_t parent, const std::string& name);
std::vector<std::string> children(hid_t group);

void write_doubles(hid_t parent, const std::string& name, const std::vector<double>& data,
                   std::vector<hsize_t> dims);
std::vector<double> read_doubles(hid_t parent, const std::string& name,
                                 std::vector<hsize_t>* dims = nullptr);
void write_ints(hid_t parent, const std::string& name, const std::vector<int>& data,
                std::vector<hsize_t> dims);
// The times an XDMF temporal collection shows for frames written at `times`: the times
// themselves while they increase, else the frame numbers 0, 1, 2, ... (frames written by a
// minimisation or at one clock reading would all sit at one time, and ParaView would show
// only one of them)
std::vector<double> xdmf_times(const std::vector<double>& times);
void write_string(hid_t parent, const std::string& name, const std::string& s);
std::string read_string(hid_t parent, const std::string& name);

void attr_string(hid_t obj, const std::string& name, const std::string& value);
void attr_strings(hid_t obj, const std::string& name, const std::vector<std::string>& values);
void attr_ints(hid_t obj, const std::string& name, const std::vector<int>& values);
// An integer attribute of scalar dataspace (H5MD's box/dimension).
void attr_int(hid_t obj, const std::string& name, int value);
// An attribute holding an HDF5 object reference to `path` of `file` (H5MD's particles_group).
void attr_reference(hid_t obj, const std::string& name, hid_t file, const std::string& path);
std::string read_attr_string(hid_t obj, const std::string& name);

// A time series following H5MD: <group>/step, <group>/time, <group>/value with
// value extendable in frames and in the particle dimension: [frames][rows][ncomp], or
// [frames][rows] for ncomp = 1 (H5MD 1.1: a scalar per particle has no component axis).
class TimeSeries {
 public:
  // An integer series has the fill value -1: the rows past a frame's own count (and of
  // frames written before the count grew) read -1, H5MD's mark of "no particle / no tuple".
  TimeSeries(hid_t parent, const std::string& name, int ncomp, bool integer);
  // Appends one frame of n rows (ncomp values each); returns the frame index.
  long append(long step, double time, const double* data, size_t n);
  long frames() const { return frames_; }
  hsize_t capacity() const { return nmax_; }

 private:
  Handle group_, step_, time_, value_;
  int ncomp_;
  bool integer_;
  long frames_ = 0;
  hsize_t nmax_ = 0;
};

// A scalar observable following H5MD: <group>/step, <group>/time, <group>/value[frames]
// (integer values).
class ScalarSeries {
 public:
  ScalarSeries(hid_t parent, const std::string& name);
  void append(long step, double time, double value);

 private:
  Handle group_, step_, time_, value_;
  long frames_ = 0;
};

// XDMF DataItem selecting frame t (n rows of nc values) of an extendable
// <frames> x <cap> x nc HDF5 dataset `path` in file `file` (<frames> x <cap> for nc = 1, as
// TimeSeries writes it), for ParaView.
std::string xdmf_slab(const std::string& file, const std::string& path, long t, size_t n, int nc,
                      size_t cap, long frames, const char* type);

}  // namespace slender::h5
#endif
