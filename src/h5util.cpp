#include "h5util.hpp"

#include "file_check.hpp"

#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

namespace slender::h5 {

namespace {
void check(herr_t e, const std::string& what) {
  if (e < 0) throw std::runtime_error("HDF5 error: " + what);
}
Handle checked(hid_t id, herr_t (*closer)(hid_t), const std::string& what) {
  if (id < 0) throw std::runtime_error("HDF5 error: " + what);
  return Handle(id, closer);
}
}  // namespace

// The library prints a trace of its internals for every failed call; our messages say what
// failed and why, once, so its printing is turned off when slender first touches a file.
static void quiet_library() {
  static const bool once = (H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr), true);
  (void)once;
}

Handle create_file(const std::string& path) {
  quiet_library();
  hid_t f = -1;
  H5E_BEGIN_TRY {
    f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  }
  H5E_END_TRY;
  if (f < 0) {
    std::string why = why_not_writable(path);
    if (why.empty()) why = "the file may be open in another program (HDF5 locks files it writes)";
    throw std::runtime_error("cannot create HDF5 file '" + path + "': " + why);
  }
  return Handle(f, H5Fclose);
}
Handle open_file(const std::string& path, bool writable) {
  quiet_library();
  H5E_BEGIN_TRY {
    hid_t f = H5Fopen(path.c_str(), writable ? H5F_ACC_RDWR : H5F_ACC_RDONLY, H5P_DEFAULT);
    if (f >= 0) return Handle(f, H5Fclose);
  }
  H5E_END_TRY;
  namespace fs = std::filesystem;
  std::error_code ec;
  std::string why = "not an HDF5 file, or damaged";
  if (!fs::exists(path, ec))
    why = "no such file";
  else if (fs::is_directory(path, ec))
    why = "it is a folder";
  else if (::access(path.c_str(), writable ? (R_OK | W_OK) : R_OK) != 0)
    why = std::string(writable ? "not readable and writable" : "not readable") + " (" +
          std::strerror(errno) + ")";
  throw std::runtime_error("cannot open HDF5 file '" + path + "': " + why);
}
Handle create_group(hid_t parent, const std::string& name) {
  return checked(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
                 "cannot create group " + name);
}
Handle open_group(hid_t parent, const std::string& name) {
  return checked(H5Gopen2(parent, name.c_str(), H5P_DEFAULT), H5Gclose, "missing group " + name);
}
bool exists(hid_t parent, const std::string& name) {
  htri_t r;
  H5E_BEGIN_TRY {
    r = H5Lexists(parent, name.c_str(), H5P_DEFAULT);
  }
  H5E_END_TRY;
  return r > 0;
}
std::vector<std::string> children(hid_t group) {
  std::vector<std::string> out;
  H5G_info_t info;
  check(H5Gget_info(group, &info), "group info");
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    ssize_t len =
        H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
    std::string s(static_cast<size_t>(len), '\0');
    H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i, s.data(), len + 1, H5P_DEFAULT);
    out.push_back(s);
  }
  return out;
}

namespace {
// A dataset of `dims` holding `data` (null: left empty) of the native type `type`.
void write_dataset(hid_t parent, const std::string& name, hid_t type, const void* data,
                   const std::vector<hsize_t>& dims) {
  Handle space = checked(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
                         H5Sclose, "dataspace");
  Handle ds =
      checked(H5Dcreate2(parent, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
              H5Dclose, "cannot create dataset " + name);
  if (data) check(H5Dwrite(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "write " + name);
}
}  // namespace

void write_doubles(hid_t parent, const std::string& name, const std::vector<double>& data,
                   std::vector<hsize_t> dims) {
  write_dataset(parent, name, H5T_NATIVE_DOUBLE, data.empty() ? nullptr : data.data(), dims);
}

void write_ints(hid_t parent, const std::string& name, const std::vector<int>& data,
                std::vector<hsize_t> dims) {
  write_dataset(parent, name, H5T_NATIVE_INT, data.empty() ? nullptr : data.data(), dims);
}

std::vector<double> xdmf_times(const std::vector<double>& times) {
  for (std::size_t k = 1; k < times.size(); ++k)
    if (!(times[k] > times[k - 1])) {
      std::vector<double> index(times.size());
      for (std::size_t j = 0; j < index.size(); ++j) index[j] = static_cast<double>(j);
      return index;
    }
  return times;
}

std::vector<double> read_doubles(hid_t parent, const std::string& name,
                                 std::vector<hsize_t>* dims_out) {
  Handle ds =
      checked(H5Dopen2(parent, name.c_str(), H5P_DEFAULT), H5Dclose, "missing dataset " + name);
  Handle space = checked(H5Dget_space(ds), H5Sclose, "dataspace of " + name);
  int rank = H5Sget_simple_extent_ndims(space);
  std::vector<hsize_t> dims(static_cast<size_t>(rank));
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  size_t n = 1;
  for (auto d : dims) n *= d;
  std::vector<double> out(n);
  if (n)
    check(H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()),
          "read " + name);
  if (dims_out) *dims_out = dims;
  return out;
}

void write_string(hid_t parent, const std::string& name, const std::string& s) {
  std::vector<double> bytes(s.begin(), s.end());
  write_doubles(parent, name, bytes, {bytes.size()});
}
std::string read_string(hid_t parent, const std::string& name) {
  auto bytes = read_doubles(parent, name);
  std::string s;
  // one value per character; a value that is no character (a damaged file) reads as '?', so
  // the caller's parse of the text fails with its own message (found by fuzzing)
  for (double b : bytes)
    s.push_back(b >= -128.0 && b <= 127.0 && b == std::trunc(b) ? static_cast<char>(b) : '?');
  return s;
}

void attr_string(hid_t obj, const std::string& name, const std::string& value) {
  Handle type = checked(H5Tcopy(H5T_C_S1), H5Tclose, "string type");
  H5Tset_size(type, value.size() + 1);
  H5Tset_strpad(type, H5T_STR_NULLTERM);
  Handle space = checked(H5Screate(H5S_SCALAR), H5Sclose, "scalar space");
  Handle a = checked(H5Acreate2(obj, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                     "attribute " + name);
  check(H5Awrite(a, type, value.c_str()), "write attribute " + name);
}
void attr_strings(hid_t obj, const std::string& name, const std::vector<std::string>& values) {
  size_t len = 1;
  for (auto& v : values) len = std::max(len, v.size() + 1);
  std::vector<char> buf(len * values.size(), '\0');
  for (size_t i = 0; i < values.size(); ++i) values[i].copy(&buf[i * len], values[i].size());
  Handle type = checked(H5Tcopy(H5T_C_S1), H5Tclose, "string type");
  H5Tset_size(type, len);
  hsize_t n = values.size();
  Handle space = checked(H5Screate_simple(1, &n, nullptr), H5Sclose, "space");
  Handle a = checked(H5Acreate2(obj, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                     "attribute " + name);
  check(H5Awrite(a, type, buf.data()), "write attribute " + name);
}
void attr_ints(hid_t obj, const std::string& name, const std::vector<int>& values) {
  hsize_t n = values.size();
  Handle space = checked(H5Screate_simple(1, &n, nullptr), H5Sclose, "space");
  Handle a = checked(H5Acreate2(obj, name.c_str(), H5T_STD_I32LE, space, H5P_DEFAULT, H5P_DEFAULT),
                     H5Aclose, "attribute " + name);
  check(H5Awrite(a, H5T_NATIVE_INT, values.data()), "write attribute " + name);
}
void attr_int(hid_t obj, const std::string& name, int value) {
  Handle space = checked(H5Screate(H5S_SCALAR), H5Sclose, "scalar space");
  Handle a = checked(H5Acreate2(obj, name.c_str(), H5T_STD_I32LE, space, H5P_DEFAULT, H5P_DEFAULT),
                     H5Aclose, "attribute " + name);
  check(H5Awrite(a, H5T_NATIVE_INT, &value), "write attribute " + name);
}
void attr_reference(hid_t obj, const std::string& name, hid_t file, const std::string& path) {
  hobj_ref_t ref;
  check(H5Rcreate(&ref, file, path.c_str(), H5R_OBJECT, -1), "reference to " + path);
  Handle space = checked(H5Screate(H5S_SCALAR), H5Sclose, "scalar space");
  Handle a =
      checked(H5Acreate2(obj, name.c_str(), H5T_STD_REF_OBJ, space, H5P_DEFAULT, H5P_DEFAULT),
              H5Aclose, "attribute " + name);
  check(H5Awrite(a, H5T_STD_REF_OBJ, &ref), "write attribute " + name);
}
std::string read_attr_string(hid_t obj, const std::string& name) {
  Handle a = checked(H5Aopen(obj, name.c_str(), H5P_DEFAULT), H5Aclose, "attribute " + name);
  Handle type = checked(H5Aget_type(a), H5Tclose, "attribute type");
  size_t len = H5Tget_size(type);
  std::string s(len, '\0');
  check(H5Aread(a, type, s.data()), "read attribute " + name);
  while (!s.empty() && s.back() == '\0') s.pop_back();
  return s;
}

namespace {
// Writes entry t of an extendable rank-1 dataset (the step, time or scalar value of frame t).
void write_frame(hsize_t t, const Handle& ds, hid_t memtype, const void* v) {
  hsize_t size = t + 1;
  check(H5Dset_extent(ds, &size), "extend");
  Handle fs = checked(H5Dget_space(ds), H5Sclose, "space");
  hsize_t start = t, count = 1;
  H5Sselect_hyperslab(fs, H5S_SELECT_SET, &start, nullptr, &count, nullptr);
  Handle ms = checked(H5Screate_simple(1, &count, nullptr), H5Sclose, "space");
  check(H5Dwrite(ds, memtype, ms, fs, H5P_DEFAULT, v), "write frame");
}
}  // namespace

TimeSeries::TimeSeries(hid_t parent, const std::string& name, int ncomp, bool integer)
    : ncomp_(ncomp), integer_(integer) {
  group_ = create_group(parent, name);
  // value [frames][rows][components], or [frames][rows] for one component (H5MD 1.1: a
  // scalar per particle has no component axis)
  const int vrank = ncomp_ == 1 ? 2 : 3;
  auto make = [&](const char* nm, hid_t type, int rank, const hsize_t* chunk) {
    std::vector<hsize_t> zero(static_cast<size_t>(rank), 0),
        maxd(static_cast<size_t>(rank), H5S_UNLIMITED);
    if (rank == 3) maxd[2] = static_cast<hsize_t>(ncomp_);
    Handle space = checked(H5Screate_simple(rank, zero.data(), maxd.data()), H5Sclose, "space");
    Handle plist = checked(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "plist");
    H5Pset_chunk(plist, rank, chunk);
    if (rank > 1 && integer) {
      const long long fill = -1;
      H5Pset_fill_value(plist, H5T_NATIVE_LLONG, &fill);
    }
    return checked(H5Dcreate2(group_, nm, type, space, H5P_DEFAULT, plist, H5P_DEFAULT), H5Dclose,
                   std::string("dataset ") + nm);
  };
  const hsize_t c1[1] = {64};
  step_ = make("step", H5T_STD_I64LE, 1, c1);
  time_ = make("time", H5T_IEEE_F64LE, 1, c1);
  const hsize_t c3[3] = {1, 1024, static_cast<hsize_t>(ncomp_)};
  value_ = make("value", integer ? H5T_STD_I64LE : H5T_IEEE_F64LE, vrank, c3);
}

long TimeSeries::append(long step, double time, const double* data, size_t n) {
  const hsize_t t = static_cast<hsize_t>(frames_);
  nmax_ = std::max<hsize_t>(nmax_, n);
  long long s = step;
  write_frame(t, step_, H5T_NATIVE_LLONG, &s);
  write_frame(t, time_, H5T_NATIVE_DOUBLE, &time);
  const int vrank = ncomp_ == 1 ? 2 : 3;  // as created
  hsize_t size[3] = {t + 1, nmax_, static_cast<hsize_t>(ncomp_)};
  check(H5Dset_extent(value_, size), "extend value");
  Handle fs = checked(H5Dget_space(value_), H5Sclose, "space");
  hsize_t start[3] = {t, 0, 0}, count[3] = {1, n, static_cast<hsize_t>(ncomp_)};
  H5Sselect_hyperslab(fs, H5S_SELECT_SET, start, nullptr, count, nullptr);
  Handle ms = checked(H5Screate_simple(vrank, count, nullptr), H5Sclose, "space");
  if (integer_) {
    std::vector<long long> buf(n * static_cast<size_t>(ncomp_));
    for (size_t i = 0; i < buf.size(); ++i) buf[i] = static_cast<long long>(data[i]);
    check(H5Dwrite(value_, H5T_NATIVE_LLONG, ms, fs, H5P_DEFAULT, buf.data()), "write value");
  } else {
    check(H5Dwrite(value_, H5T_NATIVE_DOUBLE, ms, fs, H5P_DEFAULT, data), "write value");
  }
  return frames_++;
}

ScalarSeries::ScalarSeries(hid_t parent, const std::string& name) {
  group_ = create_group(parent, name);
  auto make = [&](const char* nm, hid_t type) {
    hsize_t zero = 0, maxd = H5S_UNLIMITED, chunk = 64;
    Handle space = checked(H5Screate_simple(1, &zero, &maxd), H5Sclose, "space");
    Handle plist = checked(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "plist");
    H5Pset_chunk(plist, 1, &chunk);
    return checked(H5Dcreate2(group_, nm, type, space, H5P_DEFAULT, plist, H5P_DEFAULT), H5Dclose,
                   std::string("dataset ") + nm);
  };
  step_ = make("step", H5T_STD_I64LE);
  time_ = make("time", H5T_IEEE_F64LE);
  value_ = make("value", H5T_STD_I64LE);
}

void ScalarSeries::append(long step, double time, double value) {
  const hsize_t t = static_cast<hsize_t>(frames_);
  const long long s = step, v = static_cast<long long>(value);
  write_frame(t, step_, H5T_NATIVE_LLONG, &s);
  write_frame(t, time_, H5T_NATIVE_DOUBLE, &time);
  write_frame(t, value_, H5T_NATIVE_LLONG, &v);
  ++frames_;
}

std::string xdmf_slab(const std::string& file, const std::string& path, long t, size_t n, int nc,
                      size_t cap, long frames, const char* type) {
  char head[512];
  if (nc == 1) {  // a [frames][rows] dataset (TimeSeries of one component)
    std::snprintf(
        head, sizeof head,
        "<DataItem ItemType=\"HyperSlab\" Dimensions=\"%zu\" Type=\"HyperSlab\">\n"
        "  <DataItem Dimensions=\"3 2\" Format=\"XML\">%ld 0 1 1 1 %zu</DataItem>\n"
        "  <DataItem Dimensions=\"%ld %zu\" NumberType=\"%s\" Precision=\"8\" Format=\"HDF\">",
        n, t, n, frames, cap, type);
    return std::string(head) + file + ":" + path + "</DataItem>\n</DataItem>\n";
  }
  std::snprintf(
      head, sizeof head,
      "<DataItem ItemType=\"HyperSlab\" Dimensions=\"%zu %d\" Type=\"HyperSlab\">\n"
      "  <DataItem Dimensions=\"3 3\" Format=\"XML\">%ld 0 0 1 1 1 1 %zu %d</DataItem>\n"
      "  <DataItem Dimensions=\"%ld %zu %d\" NumberType=\"%s\" Precision=\"8\" Format=\"HDF\">",
      n, nc, t, n, nc, frames, cap, nc, type);
  return std::string(head) + file + ":" + path + "</DataItem>\n</DataItem>\n";
}

}  // namespace slender::h5
