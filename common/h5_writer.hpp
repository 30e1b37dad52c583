#pragma once
// What a run writes besides metrics.json: OUT/run.h5 with the particle frames, the time series of
// the measures and the run's metadata, and OUT/run.xdmf describing the frames for ParaView.
//
// run.h5 layout
//   /meta                 attributes scene, method, git_commit (strings), spacing (m),
//                         boundary_names (the walls then rigid bodies, one per line);
//                         dataset scene_toml (the resolved scene, one string)
//   /frames/NNNNNN        attribute time (s); datasets, n = particles:
//       position, velocity, displacement   n x 3 (z = 0: plane problems in XYZ geometry)
//       stress, strain                     n x 9 (full 3x3, row-major; tension positive)
//       mass, volume, density              n
//       body, material                     n (int32)
//       pressure = -tr(sigma)/3 (compression positive), von_mises = sqrt(3 J2),
//       equivalent_strain = sqrt(2/3 e:e), e the deviator of the accumulated strain   n
//       one dataset per internal variable, by its name   n (NaN where a model lacks it)
//       vertices = 0 .. n-1 (int32), the XDMF Polyvertex connectivity   n
//       walls and rigid bodies at the frame's time (absent in a scene without them):
//         boundary_points m x 3, boundary_segments k x 2 (int32, rows of boundary_points),
//         boundary k (int32: index of the wall, then rigid body, in /meta boundary_names order)
//       the SPFEM mesh in use (absent for SPH): triangles t x 3 and surface_edges e x 2 (int32,
//         particle rows; the surface edges are those of one triangle)
//   /series/<name>        1-D, one per measure column ("time" first), rewritten at each call
//
// Every write_frame / write_series ends with H5Fflush and a rewritten run.xdmf, so a run that
// stops at any point leaves a readable pair holding every frame so far. The writer opens run.h5
// without HDF5 file locking, so ParaView or h5py can read it while the run goes on.

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "common/frame_geometry.hpp"
#include "common/particles.hpp"
#include "common/tensor.hpp"
#include "common/xdmf.hpp"

namespace duet {

class RunWriter {
 public:
  /// Creates `out_dir` if needed, truncates out_dir/run.h5 and writes an empty out_dir/run.xdmf.
  /// Throws std::runtime_error naming the path on any HDF5 or file failure (as every method does).
  explicit RunWriter(const std::string& out_dir);
  ~RunWriter();
  RunWriter(const RunWriter&) = delete;
  RunWriter& operator=(const RunWriter&) = delete;

  void write_metadata(const std::string& scene_name, const std::string& method,
                      const std::string& resolved_scene_toml, const std::string& git_commit,
                      double spacing, const std::vector<std::string>& boundary_names = {});

  /// Appends frame /frames/NNNNNN (NNNNNN = number of frames so far). A frame at the same time as
  /// the previous one replaces it (the driver always writes the final state, which may coincide
  /// with the last output time).
  /// `geometry`: the walls and rigid bodies and the mesh shown with the particles.
  void write_frame(double time, const Particles& particles, const FrameGeometry& geometry = {});

  /// Writes (or rewrites) /series/<names[k]> = columns[k]; names and columns have equal length.
  void write_series(const std::vector<std::string>& names,
                    const std::vector<std::vector<double>>& columns);

  std::size_t n_frames() const { return frames_.size(); }
  const std::string& h5_path() const { return h5_path_; }
  const std::string& xdmf_path() const { return xdmf_path_; }

 private:
  void flush_and_describe();

  std::string h5_path_;
  std::string xdmf_path_;
  std::int64_t file_ = -1;  // hid_t
  std::vector<XdmfFrame> frames_;
};

/// Call first in main, before any other HDF5 call: keeps the HDF5 library from closing files at
/// exit. After a write has failed (a full disk), HDF5 1.10's own exit-time close of that file
/// crashes (SIGSEGV in H5F__close_cb) after metrics.json was written; the writer closes its files
/// itself, so nothing is lost.
void keep_hdf5_out_of_exit();

/// One frame read back from run.h5 (tests, post-processing).
struct Frame {
  double time = 0.0;
  std::vector<Vec2> position;
  std::vector<Mat3> stress;
  /// Every one-column dataset of the frame by name: mass, volume, density, body, material,
  /// pressure, von_mises, equivalent_strain and the internal variables.
  std::map<std::string, std::vector<double>> scalars;
};

/// Frame `index` of the run.h5 at `path`. Throws std::runtime_error naming the path.
Frame read_frame(const std::string& path, std::size_t index);

/// Number of frames in the run.h5 at `path`.
std::size_t count_frames(const std::string& path);

/// /series/<name> of the run.h5 at `path`.
std::vector<double> read_series(const std::string& path, const std::string& name);

struct RunMetadata {
  std::string scene;
  std::string method;
  std::string scene_toml;
  std::string git_commit;
  double spacing = 0.0;
};
RunMetadata read_metadata(const std::string& path);

/// Name of frame `index` inside run.h5: "/frames/000042".
std::string frame_group(std::size_t index);

}  // namespace duet
