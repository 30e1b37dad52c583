#include "common/h5_writer.hpp"

#include <hdf5.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <system_error>
#include <type_traits>
#include <utility>

namespace duet {

static_assert(std::is_same_v<hid_t, std::int64_t>, "RunWriter stores the file id as int64_t");

namespace {

// ---------------------------------------------------------------------------------------------
// HDF5 plumbing: quiet error stack, checked calls that throw with the path, owning handles.

/// Silences HDF5's automatic error printing for a scope; failures are reported by exceptions.
class QuietErrors {
 public:
  QuietErrors() {
    H5Eget_auto2(H5E_DEFAULT, &function_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~QuietErrors() { H5Eset_auto2(H5E_DEFAULT, function_, data_); }
  QuietErrors(const QuietErrors&) = delete;
  QuietErrors& operator=(const QuietErrors&) = delete;

 private:
  H5E_auto2_t function_ = nullptr;
  void* data_ = nullptr;
};

herr_t innermost_error(unsigned n, const H5E_error2_t* error, void* text) {
  if (n == 0 && error->desc != nullptr) *static_cast<std::string*>(text) = error->desc;
  return 0;
}

/// The innermost message of HDF5's error stack (then cleared).
std::string hdf5_error_text() {
  std::string text;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, innermost_error, &text);
  H5Eclear2(H5E_DEFAULT);
  return text;
}

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  const std::string detail = hdf5_error_text();
  throw std::runtime_error(path + ": HDF5 " + what + " failed" +
                           (detail.empty() ? std::string() : " (" + detail + ")"));
}

hid_t checked(hid_t id, const std::string& path, const std::string& what) {
  if (id < 0) fail(path, what);
  return id;
}

void checked(herr_t status, const std::string& path, const std::string& what) {
  if (status < 0) fail(path, what);
}

/// Owns an HDF5 identifier and closes it with the matching H5?close.
class Handle {
 public:
  Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  ~Handle() {
    if (id_ >= 0) close_(id_);
  }
  Handle(Handle&& other) noexcept : id_(std::exchange(other.id_, -1)), close_(other.close_) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle& operator=(Handle&&) = delete;
  hid_t get() const { return id_; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

/// File access without file locking, so that readers and the writer never lock each other out.
Handle unlocked_access(const std::string& path) {
  Handle fapl(checked(H5Pcreate(H5P_FILE_ACCESS), path, "H5Pcreate(file access)"), H5Pclose);
  checked(H5Pset_file_locking(fapl.get(), false, true), path, "H5Pset_file_locking");
  return fapl;
}

Handle open_for_reading(const std::string& path) {
  const Handle fapl = unlocked_access(path);
  return Handle(checked(H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl.get()), path, "open"), H5Fclose);
}

bool link_exists(hid_t location, const std::string& name) {
  return H5Lexists(location, name.c_str(), H5P_DEFAULT) > 0;
}

/// Dataset name for a free-form name (a measure or an internal variable): no '/' (which would
/// make groups) and not empty.
std::string dataset_name(const std::string& name) {
  std::string s = name.empty() ? std::string("unnamed") : name;
  std::replace(s.begin(), s.end(), '/', '_');
  if (s == "." || s == "..") s = "_" + s;
  return s;
}

// ---------------------------------------------------------------------------------------------
// Writing.

template <typename T>
hid_t native_type() {
  if constexpr (std::is_same_v<T, double>) {
    return H5T_NATIVE_DOUBLE;
  } else {
    static_assert(std::is_same_v<T, std::int32_t>);
    return H5T_NATIVE_INT32;
  }
}

/// Writes a contiguous dataset of `rows` x `columns` (1-D when columns == 0) under `location`.
template <typename T>
void write_dataset(hid_t location, const std::string& name, const std::vector<T>& values,
                   std::size_t rows, std::size_t columns, const std::string& path) {
  const hsize_t dims[2] = {static_cast<hsize_t>(rows), static_cast<hsize_t>(columns)};
  const Handle space(checked(H5Screate_simple(columns == 0 ? 1 : 2, dims, nullptr), path,
                             "H5Screate_simple(" + name + ")"),
                     H5Sclose);
  const Handle set(checked(H5Dcreate2(location, name.c_str(), native_type<T>(), space.get(),
                                      H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                           path, "create dataset " + name),
                   H5Dclose);
  if (values.empty()) return;
  checked(H5Dwrite(set.get(), native_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), path,
          "write dataset " + name);
}

void write_double_attribute(hid_t location, const std::string& name, double value,
                            const std::string& path) {
  const Handle space(checked(H5Screate(H5S_SCALAR), path, "H5Screate"), H5Sclose);
  const Handle attribute(checked(H5Acreate2(location, name.c_str(), H5T_NATIVE_DOUBLE, space.get(),
                                            H5P_DEFAULT, H5P_DEFAULT),
                                 path, "create attribute " + name),
                         H5Aclose);
  checked(H5Awrite(attribute.get(), H5T_NATIVE_DOUBLE, &value), path, "write attribute " + name);
}

/// Fixed-length UTF-8 string type of the string's length (at least 1), null-padded.
Handle string_type(const std::string& value, const std::string& path) {
  Handle type(checked(H5Tcopy(H5T_C_S1), path, "H5Tcopy"), H5Tclose);
  checked(H5Tset_size(type.get(), std::max<std::size_t>(value.size(), 1)), path, "H5Tset_size");
  checked(H5Tset_strpad(type.get(), H5T_STR_NULLPAD), path, "H5Tset_strpad");
  checked(H5Tset_cset(type.get(), H5T_CSET_UTF8), path, "H5Tset_cset");
  return type;
}

void write_string_attribute(hid_t location, const std::string& name, const std::string& value,
                            const std::string& path) {
  const Handle type = string_type(value, path);
  const Handle space(checked(H5Screate(H5S_SCALAR), path, "H5Screate"), H5Sclose);
  const Handle attribute(
      checked(H5Acreate2(location, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
              path, "create attribute " + name),
      H5Aclose);
  const std::string padded = value.empty() ? std::string(1, '\0') : value;
  checked(H5Awrite(attribute.get(), type.get(), padded.data()), path, "write attribute " + name);
}

void write_string_dataset(hid_t location, const std::string& name, const std::string& value,
                          const std::string& path) {
  const Handle type = string_type(value, path);
  const Handle space(checked(H5Screate(H5S_SCALAR), path, "H5Screate"), H5Sclose);
  const Handle set(checked(H5Dcreate2(location, name.c_str(), type.get(), space.get(), H5P_DEFAULT,
                                      H5P_DEFAULT, H5P_DEFAULT),
                           path, "create dataset " + name),
                   H5Dclose);
  const std::string padded = value.empty() ? std::string(1, '\0') : value;
  checked(H5Dwrite(set.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, padded.data()), path,
          "write dataset " + name);
}

/// Rows of fixed-size integer arrays, flattened row-major.
template <std::size_t N>
std::vector<std::int32_t> flat(const std::vector<std::array<std::int32_t, N>>& rows) {
  std::vector<std::int32_t> out;
  out.reserve(N * rows.size());
  for (const auto& row : rows) out.insert(out.end(), row.begin(), row.end());
  return out;
}

std::vector<double> rows_of_vec2(const std::vector<Vec2>& v) {
  std::vector<double> out(3 * v.size(), 0.0);  // z = 0
  for (std::size_t i = 0; i < v.size(); ++i) {
    out[3 * i] = v[i].x();
    out[3 * i + 1] = v[i].y();
  }
  return out;
}

std::vector<double> rows_of_mat3(const std::vector<Mat3>& m) {
  std::vector<double> out(9 * m.size());
  for (std::size_t i = 0; i < m.size(); ++i) {
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) out[9 * i + 3 * r + c] = m[i](r, c);
    }
  }
  return out;
}

/// Every array of the particle state has one entry per particle (else the writer would read past
/// the end of one of them).
void check_sizes(const Particles& p, const std::string& path) {
  const std::size_t n = p.size();
  const bool consistent = p.velocity.size() == n && p.displacement.size() == n &&
                          p.mass.size() == n && p.volume.size() == n && p.density.size() == n &&
                          p.stress.size() == n && p.strain.size() == n && p.body.size() == n &&
                          p.material.size() == n &&
                          p.internal.values.size() == n * p.internal.width;
  if (!consistent) {
    throw std::runtime_error(path +
                             ": cannot write a frame: the particle arrays differ in length "
                             "from the " +
                             std::to_string(n) + " positions");
  }
}

const char* const builtin_fields[] = {
    "position", "velocity",  "displacement",      "stress",  "strain",
    "mass",     "volume",    "density",           "body",    "material",
    "pressure", "von_mises", "equivalent_strain", "vertices"};

/// Dataset name of an internal variable: its name, prefixed when it would clash with a field.
std::string internal_dataset_name(const std::string& name) {
  const std::string s = dataset_name(name);
  for (const char* field : builtin_fields) {
    if (s == field) return "internal_" + s;
  }
  return s;
}

// ---------------------------------------------------------------------------------------------
// Reading.

std::vector<hsize_t> dataset_dims(hid_t set, const std::string& path, const std::string& name) {
  const Handle space(checked(H5Dget_space(set), path, "H5Dget_space(" + name + ")"), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0) fail(path, "rank of " + name);
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  if (rank > 0) H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  return dims;
}

/// All values of a numeric dataset as doubles (HDF5 converts integers), with its dimensions.
std::vector<double> read_doubles(hid_t location, const std::string& name, const std::string& path,
                                 std::vector<hsize_t>* dims_out = nullptr) {
  const Handle set(
      checked(H5Dopen2(location, name.c_str(), H5P_DEFAULT), path, "open dataset " + name),
      H5Dclose);
  const std::vector<hsize_t> dims = dataset_dims(set.get(), path, name);
  hsize_t count = 1;
  for (const hsize_t d : dims) count *= d;
  std::vector<double> values(count);
  if (count > 0) {
    checked(H5Dread(set.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
            path, "read dataset " + name);
  }
  if (dims_out != nullptr) *dims_out = dims;
  return values;
}

std::string read_string(hid_t object, bool is_attribute, const std::string& path,
                        const std::string& name) {
  const Handle type(
      checked(is_attribute ? H5Aget_type(object) : H5Dget_type(object), path, "type of " + name),
      H5Tclose);
  if (H5Tget_class(type.get()) != H5T_STRING || H5Tis_variable_str(type.get()) > 0) {
    throw std::runtime_error(path + ": " + name + " is not a fixed-length string");
  }
  std::string value(H5Tget_size(type.get()), '\0');
  const herr_t status =
      is_attribute ? H5Aread(object, type.get(), value.data())
                   : H5Dread(object, type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, value.data());
  checked(status, path, "read " + name);
  value.resize(value.find_last_not_of('\0') + 1);  // npos + 1 == 0: all padding
  return value;
}

std::string read_string_attribute(hid_t location, const std::string& name,
                                  const std::string& path) {
  const Handle attribute(
      checked(H5Aopen(location, name.c_str(), H5P_DEFAULT), path, "open attribute " + name),
      H5Aclose);
  return read_string(attribute.get(), true, path, name);
}

double read_double_attribute(hid_t location, const std::string& name, const std::string& path) {
  const Handle attribute(
      checked(H5Aopen(location, name.c_str(), H5P_DEFAULT), path, "open attribute " + name),
      H5Aclose);
  double value = 0.0;
  checked(H5Aread(attribute.get(), H5T_NATIVE_DOUBLE, &value), path, "read attribute " + name);
  return value;
}

/// Names of the links in `group`, in name order.
std::vector<std::string> link_names(hid_t group, const std::string& path, const std::string& what) {
  H5G_info_t info;
  checked(H5Gget_info(group, &info), path, "H5Gget_info(" + what + ")");
  std::vector<std::string> names;
  for (hsize_t k = 0; k < info.nlinks; ++k) {
    const ssize_t length =
        H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, k, nullptr, 0, H5P_DEFAULT);
    if (length < 0) fail(path, "link name in " + what);
    std::string link(static_cast<std::size_t>(length) + 1, '\0');
    H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, k, link.data(), link.size(),
                       H5P_DEFAULT);
    link.resize(static_cast<std::size_t>(length));
    names.push_back(std::move(link));
  }
  return names;
}

bool is_dataset(hid_t location, const std::string& name) {
  H5O_info_t info;
  return H5Oget_info_by_name(location, name.c_str(), &info, H5P_DEFAULT) >= 0 &&
         info.type == H5O_TYPE_DATASET;
}

bool is_integer(hid_t location, const std::string& name, const std::string& path) {
  const Handle set(
      checked(H5Dopen2(location, name.c_str(), H5P_DEFAULT), path, "open dataset " + name),
      H5Dclose);
  const Handle type(checked(H5Dget_type(set.get()), path, "type of " + name), H5Tclose);
  return H5Tget_class(type.get()) == H5T_INTEGER;
}

Handle open_group(hid_t location, const std::string& name, const std::string& path) {
  return Handle(checked(H5Gopen2(location, name.c_str(), H5P_DEFAULT), path, "open group " + name),
                H5Gclose);
}

/// The group of frame `index` in an open run.h5; throws naming the path when it lists none.
std::string listed_frame(hid_t file, std::size_t index, const std::string& path) {
  const std::string name = frame_group(index);
  if (!link_exists(file, "/frames") || !link_exists(file, name)) {
    throw std::runtime_error(path + ": no frame " + std::to_string(index) + " (" + name + ")");
  }
  return name;
}

/// The inverses of rows_of_vec2 and rows_of_mat3: rows of 3 (z dropped) and of 9 (row-major).
std::vector<Vec2> vec2_from_rows(const std::vector<double>& v) {
  std::vector<Vec2> out(v.size() / 3);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = Vec2(v[3 * i], v[3 * i + 1]);
  return out;
}

std::vector<Mat3> mat3_from_rows(const std::vector<double>& v) {
  std::vector<Mat3> out(v.size() / 9);
  for (std::size_t i = 0; i < out.size(); ++i) {
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) out[i](r, c) = v[9 * i + 3 * r + c];
    }
  }
  return out;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// RunWriter.

namespace {

/// Creates the HDF5 file `temporary`, lets `fill` write its root group, closes it (checked: the
/// close is where HDF5 writes what it holds) and renames it to `path`: whoever opens `path` sees
/// the previous complete file or this one.
template <typename Fill>
void write_whole_file(const std::string& path, Fill fill) {
  const std::string temporary = path + ".tmp";
  const Handle fapl = unlocked_access(temporary);
  hid_t file = checked(H5Fcreate(temporary.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()),
                       temporary, "create");
  try {
    const Handle root(checked(H5Gopen2(file, "/", H5P_DEFAULT), temporary, "open /"), H5Gclose);
    fill(root.get(), temporary);
  } catch (...) {
    H5Fclose(file);
    std::remove(temporary.c_str());
    throw;
  }
  checked(H5Fclose(std::exchange(file, -1)), temporary, "close");
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) throw std::runtime_error(path + ": cannot replace (" + error.message() + ")");
}

Handle create_group(hid_t location, const std::string& name, const std::string& path) {
  return Handle(checked(H5Gcreate2(location, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                        path, "create group " + name),
                H5Gclose);
}

std::string frame_number(std::size_t index) {
  return frame_group(index).substr(std::string("/frames/").size());
}

}  // namespace

std::string frame_group(std::size_t index) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "/frames/%06zu", index);
  return buffer;
}

RunWriter::RunWriter(const std::string& out_dir)
    : out_dir_(out_dir), h5_path_(out_dir + "/run.h5"), xdmf_path_(out_dir + "/run.xdmf") {
  const std::filesystem::path frames = std::filesystem::path(out_dir) / "frames";
  std::error_code error;
  std::filesystem::create_directories(out_dir, error);
  if (error)
    throw std::runtime_error(out_dir + ": cannot create directory (" + error.message() + ")");
  // An earlier run in this folder: its frame files would sit beside this run's.
  std::filesystem::remove_all(frames, error);
  if (!error) std::filesystem::create_directories(frames, error);
  if (error) {
    throw std::runtime_error(frames.string() + ": cannot create directory (" + error.message() +
                             ")");
  }
  const QuietErrors quiet;
  write_index();
}

namespace {

/// The XDMF description of a frame file written before (a resumed run's earlier frames): its
/// datasets by shape, as write_frame lists them (fields in name order).
XdmfFrame describe_frame_file(const std::string& out_dir, std::size_t index) {
  XdmfFrame frame;
  frame.name = frame_number(index);
  frame.file = "frames/" + frame.name + ".h5";
  const std::string path = out_dir + "/" + frame.file;
  const Handle file = open_for_reading(path);
  const Handle root(checked(H5Gopen2(file.get(), "/", H5P_DEFAULT), path, "open /"), H5Gclose);
  frame.time = read_double_attribute(root.get(), "time", path);
  const auto rows = [&](const std::string& name) {
    const Handle set(
        checked(H5Dopen2(root.get(), name.c_str(), H5P_DEFAULT), path, "open dataset " + name),
        H5Dclose);
    return dataset_dims(set.get(), path, name);
  };
  frame.n_points = static_cast<std::size_t>(rows(frame.geometry).at(0));
  for (const std::string& name : link_names(root.get(), path, "/")) {
    if (!is_dataset(root.get(), name)) continue;
    const std::vector<hsize_t> dims = rows(name);
    if (name == "boundary_points") {
      frame.n_boundary_points = static_cast<std::size_t>(dims.at(0));
    } else if (name == "boundary_segments") {
      frame.n_boundary_segments = static_cast<std::size_t>(dims.at(0));
    } else if (name == "triangles") {
      frame.n_triangles = static_cast<std::size_t>(dims.at(0));
    } else if (name == "surface_edges") {
      frame.n_surface_edges = static_cast<std::size_t>(dims.at(0));
    } else if (name == frame.geometry || name == frame.vertices || name == "boundary") {
      continue;
    } else if (dims.size() == 2 && dims[1] == 3) {
      frame.fields.push_back({name, "Vector", 3, "Float", 8});
    } else if (dims.size() == 2 && dims[1] == 9) {
      frame.fields.push_back({name, "Tensor", 9, "Float", 8});
    } else if (dims.size() == 1) {
      const bool integer = is_integer(root.get(), name, path);
      frame.fields.push_back({name, "Scalar", 1, integer ? "Int" : "Float", integer ? 4 : 8});
    }
  }
  return frame;
}

}  // namespace

RunWriter::RunWriter(const std::string& out_dir, ContinueAfter from)
    : out_dir_(out_dir), h5_path_(out_dir + "/run.h5"), xdmf_path_(out_dir + "/run.xdmf") {
  const QuietErrors quiet;
  for (std::size_t k = 0; k <= from.frame; ++k) frames_.push_back(describe_frame_file(out_dir, k));
  // Frames after it (and a frame file half-written when the run stopped) are this run's to write.
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(out_dir + "/frames", error)) {
    const std::string name = entry.path().filename().string();
    // NNNNNN.h5 with NNNNNN <= frame (digits checked before they are read as a number)
    const bool kept = name.size() == 9 && name.compare(6, 3, ".h5") == 0 &&
                      name.find_first_not_of("0123456789") == 6 &&
                      std::stoul(name.substr(0, 6)) <= from.frame;
    if (!kept) std::filesystem::remove(entry.path(), error);
  }
  if (error) throw std::runtime_error(out_dir + "/frames: " + error.message());
}

void RunWriter::write_index() const {
  write_whole_file(h5_path_, [&](hid_t root, const std::string& path) {
    const Handle meta = create_group(root, "meta", path);
    if (metadata_) {
      const Metadata& m = *metadata_;
      write_string_attribute(meta.get(), "scene", m.scene, path);
      write_string_attribute(meta.get(), "method", m.method, path);
      write_string_attribute(meta.get(), "git_commit", m.git_commit, path);
      write_double_attribute(meta.get(), "spacing", m.spacing, path);
      write_string_attribute(meta.get(), "boundary_names", m.boundary_names, path);
      write_string_dataset(meta.get(), "scene_toml", m.scene_toml, path);
    }
    const Handle frames = create_group(root, "frames", path);
    for (const XdmfFrame& frame : frames_) {
      checked(H5Lcreate_external(frame.file.c_str(), "/", frames.get(), frame.name.c_str(),
                                 H5P_DEFAULT, H5P_DEFAULT),
              path, "link frame " + frame.name);
    }
    const Handle series = create_group(root, "series", path);
    for (std::size_t k = 0; k < series_names_.size(); ++k) {
      const std::string name = dataset_name(series_names_[k]);
      // Two names that differ only by '/' share a dataset: the later one is kept.
      if (link_exists(series.get(), name)) {
        checked(H5Ldelete(series.get(), name.c_str(), H5P_DEFAULT), path, "delete " + name);
      }
      write_dataset(series.get(), name, series_columns_[k], series_columns_[k].size(), 0, path);
    }
  });
  // After run.h5: the XDMF never names a frame that run.h5 does not.
  write_xdmf(xdmf_path_, frames_);
}

void RunWriter::write_metadata(const std::string& scene_name, const std::string& method,
                               const std::string& resolved_scene_toml,
                               const std::string& git_commit, double spacing,
                               const std::vector<std::string>& boundary_names) {
  const QuietErrors quiet;
  Metadata m{scene_name, method, resolved_scene_toml, git_commit, {}, spacing};
  for (const std::string& name : boundary_names) {
    m.boundary_names += (m.boundary_names.empty() ? "" : "\n") + name;
  }
  metadata_ = std::move(m);
  write_index();
}

void RunWriter::write_frame(double time, const Particles& particles, const FrameGeometry& geometry,
                            const StateBag* state) {
  const QuietErrors quiet;
  check_sizes(particles, h5_path_);
  // Same time as the previous frame: replace it (its file is renamed over).
  if (!frames_.empty() && frames_.back().time == time) frames_.pop_back();

  XdmfFrame frame;
  frame.time = time;
  frame.name = frame_number(frames_.size());
  frame.file = "frames/" + frame.name + ".h5";
  const std::size_t n = particles.size();
  write_whole_file(out_dir_ + "/" + frame.file, [&](hid_t g, const std::string& path) {
    write_double_attribute(g, "time", time, path);
    const auto vector3 = [&](const std::string& field, const std::vector<Vec2>& values) {
      write_dataset(g, field, rows_of_vec2(values), n, 3, path);
    };
    const auto tensor = [&](const std::string& field, const std::vector<Mat3>& values) {
      write_dataset(g, field, rows_of_mat3(values), n, 9, path);
      frame.fields.push_back({field, "Tensor", 9, "Float", 8});
    };
    const auto scalar = [&](const std::string& field, const std::vector<double>& values) {
      write_dataset(g, field, values, n, 0, path);
      frame.fields.push_back({field, "Scalar", 1, "Float", 8});
    };
    const auto integer = [&](const std::string& field, const std::vector<std::int32_t>& values) {
      write_dataset(g, field, values, n, 0, path);
      frame.fields.push_back({field, "Scalar", 1, "Int", 4});
    };

    std::vector<std::int32_t> vertices(n);
    for (std::size_t i = 0; i < n; ++i) vertices[i] = static_cast<std::int32_t>(i);
    write_dataset(g, frame.vertices, vertices, n, 0, path);
    frame.n_points = n;
    vector3("position", particles.position);
    vector3("velocity", particles.velocity);
    frame.fields.push_back({"velocity", "Vector", 3, "Float", 8});
    vector3("displacement", particles.displacement);
    frame.fields.push_back({"displacement", "Vector", 3, "Float", 8});
    tensor("stress", particles.stress);
    tensor("strain", particles.strain);
    scalar("mass", particles.mass);
    scalar("volume", particles.volume);
    scalar("density", particles.density);
    integer("body", particles.body);
    integer("material", particles.material);

    std::vector<double> pressure(n), q(n), equivalent_strain(n);
    for (std::size_t i = 0; i < n; ++i) {
      pressure[i] = -mean_stress(particles.stress[i]);  // p = -tr(sigma)/3, compression positive
      q[i] = von_mises(particles.stress[i]);            // q = sqrt(3 J2)
      const Mat3 e = deviator(particles.strain[i]);
      equivalent_strain[i] = std::sqrt(2.0 / 3.0 * contract(e, e));  // sqrt(2/3 e:e)
    }
    scalar("pressure", pressure);
    scalar("von_mises", q);
    scalar("equivalent_strain", equivalent_strain);

    const InternalVariables& internal = particles.internal;
    std::vector<double> values(n);
    for (std::size_t k = 0; k < internal.n_variables(); ++k) {
      for (std::size_t i = 0; i < n; ++i) {
        const std::int32_t material = particles.material[i];
        const bool known =
            material >= 0 && static_cast<std::size_t>(material) < internal.slot.size();
        values[i] = known ? internal.value(i, material, k) : std::nan("");
      }
      scalar(internal_dataset_name(internal.names[k]), values);
    }

    const BoundaryLines& lines = geometry.boundaries;
    if (!lines.segments.empty()) {
      frame.n_boundary_points = lines.points.size();
      frame.n_boundary_segments = lines.segments.size();
      write_dataset(g, "boundary_points", rows_of_vec2(lines.points), lines.points.size(), 3, path);
      write_dataset(g, "boundary_segments", flat(lines.segments), lines.segments.size(), 2, path);
      write_dataset(g, "boundary", lines.owner, lines.owner.size(), 0, path);
    }
    if (geometry.triangles && !geometry.triangles->empty()) {
      const std::vector<MeshTriangle>& triangles = *geometry.triangles;
      const std::vector<MeshEdge> edges = surface_edges(triangles);
      frame.n_triangles = triangles.size();
      frame.n_surface_edges = edges.size();
      write_dataset(g, "triangles", flat(triangles), triangles.size(), 3, path);
      write_dataset(g, "surface_edges", flat(edges), edges.size(), 2, path);
    }
    if (state) {
      const Handle group = create_group(g, "state", path);
      for (const auto& [key, values] : *state) {
        write_dataset(group.get(), dataset_name(key), values, values.size(), 0, path);
      }
    }
  });
  frames_.push_back(std::move(frame));
  write_index();
}

void RunWriter::set_series(const std::vector<std::string>& names,
                           const std::vector<std::vector<double>>& columns) {
  if (names.size() != columns.size()) {
    throw std::runtime_error(h5_path_ + ": series of " + std::to_string(names.size()) +
                             " names for " + std::to_string(columns.size()) + " columns");
  }
  series_names_ = names;
  series_columns_ = columns;
}

void RunWriter::write_series(const std::vector<std::string>& names,
                             const std::vector<std::vector<double>>& columns) {
  set_series(names, columns);
  const QuietErrors quiet;
  write_index();
}

// ---------------------------------------------------------------------------------------------
// Reading back.

Frame read_frame(const std::string& path, std::size_t index) {
  const QuietErrors quiet;
  const Handle file = open_for_reading(path);
  const std::string name = listed_frame(file.get(), index, path);
  const Handle group = open_group(file.get(), name, path);
  Frame frame;
  frame.time = read_double_attribute(group.get(), "time", path);
  frame.position = vec2_from_rows(read_doubles(group.get(), "position", path));
  frame.stress = mat3_from_rows(read_doubles(group.get(), "stress", path));

  for (const std::string& link : link_names(group.get(), path, name)) {
    if (!is_dataset(group.get(), link)) continue;  // the state group
    std::vector<hsize_t> dims;
    std::vector<double> values = read_doubles(group.get(), link, path, &dims);
    if (dims.size() == 1 && link != "vertices") frame.scalars.emplace(link, std::move(values));
  }
  return frame;
}

StateBag read_state(const std::string& path, std::size_t index) {
  const QuietErrors quiet;
  const Handle file = open_for_reading(path);
  StateBag state;
  const std::string group_name = listed_frame(file.get(), index, path) + "/state";
  if (!link_exists(file.get(), group_name)) return state;
  const Handle group = open_group(file.get(), group_name, path);
  for (const std::string& key : link_names(group.get(), path, group_name)) {
    state[key] = read_doubles(group.get(), key, path);
  }
  return state;
}

void read_particle_state(const std::string& path, std::size_t index, Particles& particles) {
  const QuietErrors quiet;
  const Handle file = open_for_reading(path);
  const std::string name = listed_frame(file.get(), index, path);
  const Handle group = open_group(file.get(), name, path);
  const std::size_t n = particles.size();
  const auto values = [&](const std::string& field, std::size_t columns) {
    std::vector<double> v = read_doubles(group.get(), field, path);
    if (v.size() != n * columns) {
      throw std::runtime_error(path + ": " + name + "/" + field + " holds " +
                               std::to_string(v.size() / columns) + " particles, not " +
                               std::to_string(n));
    }
    return v;
  };
  particles.position = vec2_from_rows(values("position", 3));
  particles.velocity = vec2_from_rows(values("velocity", 3));
  particles.displacement = vec2_from_rows(values("displacement", 3));
  particles.stress = mat3_from_rows(values("stress", 9));
  particles.strain = mat3_from_rows(values("strain", 9));
  particles.mass = values("mass", 1);
  particles.volume = values("volume", 1);
  particles.density = values("density", 1);
  const std::vector<double> body = values("body", 1);
  const std::vector<double> material = values("material", 1);
  for (std::size_t i = 0; i < n; ++i) {
    particles.body[i] = static_cast<std::int32_t>(body[i]);
    particles.material[i] = static_cast<std::int32_t>(material[i]);
  }
}

std::size_t count_frames(const std::string& path) {
  const QuietErrors quiet;
  const Handle file = open_for_reading(path);
  const Handle group = open_group(file.get(), "/frames", path);
  H5G_info_t info;
  checked(H5Gget_info(group.get(), &info), path, "H5Gget_info(/frames)");
  return static_cast<std::size_t>(info.nlinks);
}

std::vector<double> read_series(const std::string& path, const std::string& name) {
  const QuietErrors quiet;
  const Handle file = open_for_reading(path);
  const std::string dataset = "/series/" + dataset_name(name);
  if (!link_exists(file.get(), "/series") || !link_exists(file.get(), dataset)) {
    throw std::runtime_error(path + ": no series " + name);
  }
  return read_doubles(file.get(), dataset, path);
}

RunMetadata read_metadata(const std::string& path) {
  const QuietErrors quiet;
  const Handle file = open_for_reading(path);
  const Handle meta = open_group(file.get(), "/meta", path);
  RunMetadata m;
  m.scene = read_string_attribute(meta.get(), "scene", path);
  m.method = read_string_attribute(meta.get(), "method", path);
  m.git_commit = read_string_attribute(meta.get(), "git_commit", path);
  m.spacing = read_double_attribute(meta.get(), "spacing", path);
  const Handle set(checked(H5Dopen2(meta.get(), "scene_toml", H5P_DEFAULT), path,
                           "open dataset /meta/scene_toml"),
                   H5Dclose);
  m.scene_toml = read_string(set.get(), false, path, "/meta/scene_toml");
  return m;
}

void keep_hdf5_out_of_exit() {
  H5dont_atexit();
}

}  // namespace duet
