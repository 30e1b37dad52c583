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

/// Writes `values` into the 1-D extendible dataset `name` (created chunked on first use, then
/// resized), so a series rewritten at every frame does not leave dead copies in the file.
void write_extendible(hid_t location, const std::string& name, const std::vector<double>& values,
                      const std::string& path) {
  const hsize_t size = values.size();
  if (!link_exists(location, name)) {
    const hsize_t zero = 0;
    const hsize_t unlimited = H5S_UNLIMITED;
    const hsize_t chunk = 1024;
    const Handle space(checked(H5Screate_simple(1, &zero, &unlimited), path, "H5Screate_simple"),
                       H5Sclose);
    const Handle properties(checked(H5Pcreate(H5P_DATASET_CREATE), path, "H5Pcreate"), H5Pclose);
    checked(H5Pset_chunk(properties.get(), 1, &chunk), path, "H5Pset_chunk");
    const Handle created(checked(H5Dcreate2(location, name.c_str(), H5T_NATIVE_DOUBLE, space.get(),
                                            H5P_DEFAULT, properties.get(), H5P_DEFAULT),
                                 path, "create dataset " + name),
                         H5Dclose);
  }
  const Handle set(
      checked(H5Dopen2(location, name.c_str(), H5P_DEFAULT), path, "open dataset " + name),
      H5Dclose);
  checked(H5Dset_extent(set.get(), &size), path, "resize dataset " + name);
  if (size == 0) return;
  checked(H5Dwrite(set.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
          path, "write dataset " + name);
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

}  // namespace

std::string frame_group(std::size_t index) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "/frames/%06zu", index);
  return buffer;
}

// ---------------------------------------------------------------------------------------------
// RunWriter.

RunWriter::RunWriter(const std::string& out_dir)
    : h5_path_(out_dir + "/run.h5"), xdmf_path_(out_dir + "/run.xdmf") {
  std::error_code error;
  std::filesystem::create_directories(out_dir, error);
  if (error)
    throw std::runtime_error(out_dir + ": cannot create directory (" + error.message() + ")");
  const QuietErrors quiet;
  const Handle fapl = unlocked_access(h5_path_);
  file_ = checked(H5Fcreate(h5_path_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()), h5_path_,
                  "create");
  for (const char* group : {"/meta", "/frames", "/series"}) {
    const Handle g(checked(H5Gcreate2(file_, group, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                           h5_path_, std::string("create group ") + group),
                   H5Gclose);
  }
  flush_and_describe();
}

RunWriter::~RunWriter() {
  if (file_ < 0) return;
  const QuietErrors quiet;
  H5Fclose(file_);  // a destructor cannot throw; every frame was flushed when written
}

void RunWriter::flush_and_describe() {
  checked(H5Fflush(file_, H5F_SCOPE_LOCAL), h5_path_, "flush");
  // After the flush: the XDMF never names a dataset that is not on disk yet.
  write_xdmf(xdmf_path_, "run.h5", frames_);
}

void RunWriter::write_metadata(const std::string& scene_name, const std::string& method,
                               const std::string& resolved_scene_toml,
                               const std::string& git_commit, double spacing,
                               const std::vector<std::string>& boundary_names) {
  const QuietErrors quiet;
  // Written again on a second call: start from an empty group.
  checked(H5Ldelete(file_, "/meta", H5P_DEFAULT), h5_path_, "delete /meta");
  const Handle meta(checked(H5Gcreate2(file_, "/meta", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                            h5_path_, "create group /meta"),
                    H5Gclose);
  write_string_attribute(meta.get(), "scene", scene_name, h5_path_);
  write_string_attribute(meta.get(), "method", method, h5_path_);
  write_string_attribute(meta.get(), "git_commit", git_commit, h5_path_);
  write_double_attribute(meta.get(), "spacing", spacing, h5_path_);
  std::string names;
  for (const std::string& name : boundary_names) names += (names.empty() ? "" : "\n") + name;
  write_string_attribute(meta.get(), "boundary_names", names, h5_path_);
  write_string_dataset(meta.get(), "scene_toml", resolved_scene_toml, h5_path_);
  checked(H5Fflush(file_, H5F_SCOPE_LOCAL), h5_path_, "flush");
}

void RunWriter::write_frame(double time, const Particles& particles,
                            const FrameGeometry& geometry) {
  const QuietErrors quiet;
  check_sizes(particles, h5_path_);
  if (!frames_.empty() && frames_.back().time == time) {
    // Same time as the previous frame: replace it.
    frames_.pop_back();
    checked(H5Ldelete(file_, frame_group(frames_.size()).c_str(), H5P_DEFAULT), h5_path_,
            "delete " + frame_group(frames_.size()));
  }
  const std::string name = frame_group(frames_.size());
  const std::size_t n = particles.size();
  const Handle group(checked(H5Gcreate2(file_, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                             h5_path_, "create group " + name),
                     H5Gclose);
  const hid_t g = group.get();
  write_double_attribute(g, "time", time, h5_path_);

  XdmfFrame frame;
  frame.time = time;
  frame.group = name;
  frame.n_points = n;
  const auto vector3 = [&](const std::string& field, const std::vector<Vec2>& values) {
    write_dataset(g, field, rows_of_vec2(values), n, 3, h5_path_);
  };
  const auto tensor = [&](const std::string& field, const std::vector<Mat3>& values) {
    write_dataset(g, field, rows_of_mat3(values), n, 9, h5_path_);
    frame.fields.push_back({field, "Tensor", 9, "Float", 8});
  };
  const auto scalar = [&](const std::string& field, const std::vector<double>& values) {
    write_dataset(g, field, values, n, 0, h5_path_);
    frame.fields.push_back({field, "Scalar", 1, "Float", 8});
  };
  const auto integer = [&](const std::string& field, const std::vector<std::int32_t>& values) {
    write_dataset(g, field, values, n, 0, h5_path_);
    frame.fields.push_back({field, "Scalar", 1, "Int", 4});
  };

  std::vector<std::int32_t> vertices(n);
  for (std::size_t i = 0; i < n; ++i) vertices[i] = static_cast<std::int32_t>(i);
  write_dataset(g, frame.vertices, vertices, n, 0, h5_path_);
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
      const bool known = material >= 0 && static_cast<std::size_t>(material) < internal.slot.size();
      values[i] = known ? internal.value(i, material, k) : std::nan("");
    }
    scalar(internal_dataset_name(internal.names[k]), values);
  }

  const BoundaryLines& lines = geometry.boundaries;
  if (!lines.segments.empty()) {
    frame.n_boundary_points = lines.points.size();
    frame.n_boundary_segments = lines.segments.size();
    write_dataset(g, "boundary_points", rows_of_vec2(lines.points), lines.points.size(), 3,
                  h5_path_);
    write_dataset(g, "boundary_segments", flat(lines.segments), lines.segments.size(), 2, h5_path_);
    write_dataset(g, "boundary", lines.owner, lines.owner.size(), 0, h5_path_);
  }
  if (geometry.triangles && !geometry.triangles->empty()) {
    const std::vector<MeshTriangle>& triangles = *geometry.triangles;
    const std::vector<MeshEdge> edges = surface_edges(triangles);
    frame.n_triangles = triangles.size();
    frame.n_surface_edges = edges.size();
    write_dataset(g, "triangles", flat(triangles), triangles.size(), 3, h5_path_);
    write_dataset(g, "surface_edges", flat(edges), edges.size(), 2, h5_path_);
  }

  frames_.push_back(std::move(frame));
  flush_and_describe();
}

void RunWriter::write_series(const std::vector<std::string>& names,
                             const std::vector<std::vector<double>>& columns) {
  if (names.size() != columns.size()) {
    throw std::runtime_error(h5_path_ + ": write_series got " + std::to_string(names.size()) +
                             " names for " + std::to_string(columns.size()) + " columns");
  }
  const QuietErrors quiet;
  const Handle series(
      checked(H5Gopen2(file_, "/series", H5P_DEFAULT), h5_path_, "open group /series"), H5Gclose);
  for (std::size_t k = 0; k < names.size(); ++k) {
    write_extendible(series.get(), dataset_name(names[k]), columns[k], h5_path_);
  }
  checked(H5Fflush(file_, H5F_SCOPE_LOCAL), h5_path_, "flush");
}

// ---------------------------------------------------------------------------------------------
// Reading back.

Frame read_frame(const std::string& path, std::size_t index) {
  const QuietErrors quiet;
  const Handle file = open_for_reading(path);
  const std::string name = frame_group(index);
  if (!link_exists(file.get(), "/frames") || !link_exists(file.get(), name)) {
    throw std::runtime_error(path + ": no frame " + std::to_string(index) + " (" + name + ")");
  }
  const Handle group(
      checked(H5Gopen2(file.get(), name.c_str(), H5P_DEFAULT), path, "open group " + name),
      H5Gclose);
  Frame frame;
  frame.time = read_double_attribute(group.get(), "time", path);

  const std::vector<double> position = read_doubles(group.get(), "position", path);
  frame.position.resize(position.size() / 3);
  for (std::size_t i = 0; i < frame.position.size(); ++i) {
    frame.position[i] = Vec2(position[3 * i], position[3 * i + 1]);
  }
  const std::vector<double> stress = read_doubles(group.get(), "stress", path);
  frame.stress.resize(stress.size() / 9);
  for (std::size_t i = 0; i < frame.stress.size(); ++i) {
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) frame.stress[i](r, c) = stress[9 * i + 3 * r + c];
    }
  }

  H5G_info_t info;
  checked(H5Gget_info(group.get(), &info), path, "H5Gget_info(" + name + ")");
  for (hsize_t k = 0; k < info.nlinks; ++k) {
    const ssize_t length = H5Lget_name_by_idx(group.get(), ".", H5_INDEX_NAME, H5_ITER_INC, k,
                                              nullptr, 0, H5P_DEFAULT);
    if (length < 0) fail(path, "link name in " + name);
    std::string link(static_cast<std::size_t>(length) + 1, '\0');
    H5Lget_name_by_idx(group.get(), ".", H5_INDEX_NAME, H5_ITER_INC, k, link.data(), link.size(),
                       H5P_DEFAULT);
    link.resize(static_cast<std::size_t>(length));
    std::vector<hsize_t> dims;
    std::vector<double> values = read_doubles(group.get(), link, path, &dims);
    if (dims.size() == 1 && link != "vertices") frame.scalars.emplace(link, std::move(values));
  }
  return frame;
}

std::size_t count_frames(const std::string& path) {
  const QuietErrors quiet;
  const Handle file = open_for_reading(path);
  const Handle group(
      checked(H5Gopen2(file.get(), "/frames", H5P_DEFAULT), path, "open group /frames"), H5Gclose);
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
  const Handle meta(checked(H5Gopen2(file.get(), "/meta", H5P_DEFAULT), path, "open group /meta"),
                    H5Gclose);
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
