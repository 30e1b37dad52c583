#pragma once
// What a run writes besides metrics.json: OUT/run.h5 with the particle frames, the time series of
// the measures and the run's metadata, and OUT/run.xdmf describing the frames for ParaView.
//
// Files
//   OUT/frames/NNNNNN.h5  one file per frame, written to NNNNNN.h5.tmp, closed, then renamed:
//                         a frame file that exists is complete.
//   OUT/run.h5            the index, rebuilt in run.h5.tmp and renamed over run.h5 after every
//                         frame and series write: it is always a whole file (a process killed
//                         during an in-place HDF5 flush can lose a group's index; issue 17).
//   OUT/run.xdmf          replaced (temporary + rename) after run.h5.
//
// run.h5 layout
//   /meta                 attributes scene, method, git_commit (strings), spacing (m),
//                         boundary_names (the walls then rigid bodies, one per line);
//                         dataset scene_toml (the resolved scene, one string)
//   /frames/NNNNNN        external link to frames/NNNNNN.h5:/ (HDF5 and h5py follow it, relative
//                         to run.h5's folder), whose root holds: attribute time (s); datasets,
//                         n = particles:
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
//       state/<key>   what `duet run --resume` needs besides these fields (common/state_bag.hpp),
//                     in the frames of a method that can resume
//   /series/<name>        1-D, one per measure column ("time" first), the latest full columns
//
// A run that stops at any point, SIGKILL included, leaves a run.h5 and run.xdmf that name only
// complete frame files. Files are opened without HDF5 file locking, so ParaView or h5py can read
// while the run goes on (a reader holds the run.h5 it opened; the next one is a new file).

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "common/frame_geometry.hpp"
#include "common/particles.hpp"
#include "common/state_bag.hpp"
#include "common/tensor.hpp"
#include "common/xdmf.hpp"

namespace duet {

class RunWriter {
 public:
  /// Creates `out_dir` and out_dir/frames if needed (removing an earlier run's frame files there)
  /// and writes an empty run.h5 and run.xdmf. Throws std::runtime_error naming the path on any
  /// HDF5 or file failure (as every method does).
  explicit RunWriter(const std::string& out_dir);

  /// Opens the run in `out_dir` to go on after frame `frame` (`duet run --resume`): frames 0 ..
  /// frame are kept (their files read back for the XDMF), later frame files are removed; the
  /// index is rewritten at the next write. Throws std::runtime_error naming the path.
  struct ContinueAfter {
    std::size_t frame = 0;
  };
  RunWriter(const std::string& out_dir, ContinueAfter from);
  RunWriter(const RunWriter&) = delete;
  RunWriter& operator=(const RunWriter&) = delete;

  void write_metadata(const std::string& scene_name, const std::string& method,
                      const std::string& resolved_scene_toml, const std::string& git_commit,
                      double spacing, const std::vector<std::string>& boundary_names = {});

  /// Appends frame NNNNNN (NNNNNN = number of frames so far): its file, then the index. A frame at
  /// the same time as the previous one replaces it (the driver always writes the final state, which
  /// may coincide with the last output time). `geometry`: the walls and rigid bodies and the mesh
  /// shown with the particles.
  /// `state`: what a resumed run needs besides the particle fields, written under /state.
  void write_frame(double time, const Particles& particles, const FrameGeometry& geometry = {},
                   const StateBag* state = nullptr);

  /// Holds /series/<names[k]> = columns[k] (names and columns of equal length) for the next
  /// rewrite of the index (the next frame): one rewrite per output instead of two.
  void set_series(const std::vector<std::string>& names,
                  const std::vector<std::vector<double>>& columns);

  /// set_series, then rewrites the index now.
  void write_series(const std::vector<std::string>& names,
                    const std::vector<std::vector<double>>& columns);

  std::size_t n_frames() const { return frames_.size(); }
  const std::string& h5_path() const { return h5_path_; }
  const std::string& xdmf_path() const { return xdmf_path_; }

 private:
  struct Metadata {
    std::string scene, method, scene_toml, git_commit, boundary_names;
    double spacing = 0.0;
  };
  /// Rebuilds run.h5 from what this writer holds, then run.xdmf.
  void write_index() const;

  std::string out_dir_;
  std::string h5_path_;
  std::string xdmf_path_;
  std::optional<Metadata> metadata_;
  std::vector<std::string> series_names_;
  std::vector<std::vector<double>> series_columns_;
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

/// /state of frame `index` of the run.h5 at `path` (empty when the frame has none).
StateBag read_state(const std::string& path, std::size_t index);

/// The particle arrays frame `index` holds (position, velocity, displacement, stress, strain,
/// mass, volume, density, body, material; exact) into `particles`, which must have the frame's
/// particle count. Throws std::runtime_error naming the path.
void read_particle_state(const std::string& path, std::size_t index, Particles& particles);

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

/// Name of frame `index` inside run.h5: "/frames/000042" (a link to frames/000042.h5).
std::string frame_group(std::size_t index);

}  // namespace duet
