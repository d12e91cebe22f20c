// Grasp datasets in HDF5 through its C API. Layout (docs/dataset.md):
//   /grasps/transforms, /grasps/pregrasp_transforms   N x 4 x 4, mm
//   /grasps/dofs/open, /grasps/dofs/closed             N x D
//   /grasps/breakaway/engaged (uint8), .../values      N x J: each joint's breakaway state
//   /grasps/qualities/epsilon, .../volume              N
//   /grasps/qualities/force_closure                    N, uint8
//   /grasps/qualities/held                             N, int8 (-1: not validated)
//   /grasps/validation/held (int8, -1: not validated or not tried), .../failed (uint8),
//     .../slip (mm), .../turn (rad), .../seconds       N x 6: each direction of the validation
//   /grasps/validation/directions                      6 x 3: +x, -x, +y, -y, +z, -z
//   /grasps/contacts/offsets                           N + 1, uint64: grasp i's contacts are
//                                                       rows offsets[i] .. offsets[i+1]
//   /grasps/contacts/points, .../normals               M x 3, object frame
//   /object/file, /object/name, /object/mass, /hand/file, /hand/name (files relative to the
//                                                       dataset file's folder, or absolute)
//   root attributes: schema_version, engine_version, units ("mm"), seed
// Schema 1 files (no /grasps/validation; file names as batch was given them) are still read:
// their grasps have no per-direction validation and their file names come back as stored.

#include "graspkit/io/dataset/grasp_dataset_file.hpp"

#include <fmt/format.h>
#include <hdf5.h>
#include <unistd.h>

#include <H5PLpublic.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <mutex>
#include <type_traits>

#include "graspkit/base/error.hpp"
#include "graspkit/base/file_reference.hpp"
#include "graspkit/base/input_file.hpp"
#include "graspkit/base/output_file.hpp"
#include "io/dataset/contained_read.hpp"
#include "io/dataset/hdf5_image_check.hpp"

namespace graspkit {
namespace {

namespace fs = std::filesystem;

// 2: /grasps/validation, and /object/file and /hand/file relative to the dataset file's folder.
// 3: a validated grasp's direction may be -1: not tried, as a validation that stops at the first
//    direction let go leaves the pulls it cut short (any of the six, +x too: they take their
//    steps by turns). A validated grasp has at least one direction tried.
constexpr int kSchemaVersion = 3;
constexpr int kOldestSchemaVersion = 1;
constexpr hsize_t kDirections = 6;

// The HDF5 library this Debian build gives may not be thread-safe: one call at a time.
std::mutex& hdf5Mutex() {
  static std::mutex mutex;
  return mutex;
}

// An HDF5 identifier closed at scope exit by its own close function.
class Handle {
 public:
  Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  ~Handle() {
    if (id_ >= 0) close_(id_);
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& other) noexcept : id_(other.id_), close_(other.close_) { other.id_ = -1; }
  Handle& operator=(Handle&&) = delete;
  operator hid_t() const { return id_; }
  bool valid() const { return id_ >= 0; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

class Writer {
 public:
  Writer(const fs::path& file, hid_t handle) : file_(file), handle_(handle) {
    // Object timestamps off: the same dataset gives the same bytes.
    H5Pset_obj_track_times(group_creation_, 0);
    H5Pset_obj_track_times(dataset_creation_, 0);
  }

  hid_t group(hid_t parent, const char* name) {
    groups_.push_back(std::make_unique<Handle>(
        H5Gcreate2(parent, name, H5P_DEFAULT, group_creation_, H5P_DEFAULT), &H5Gclose));
    check(*groups_.back(), name);
    return *groups_.back();
  }

  void array(hid_t parent, const char* name, hid_t type, const std::vector<hsize_t>& shape,
             const void* data) {
    Handle space(H5Screate_simple(static_cast<int>(shape.size()), shape.data(), nullptr),
                 &H5Sclose);
    Handle set(H5Dcreate2(parent, name, type, space, H5P_DEFAULT, dataset_creation_, H5P_DEFAULT),
               &H5Dclose);
    check(set, name);
    hsize_t count = 1;
    for (hsize_t n : shape) count *= n;
    if (count > 0) check(H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), name);
  }

  void scalar(hid_t parent, const char* name, hid_t type, const void* data) {
    Handle space(H5Screate(H5S_SCALAR), &H5Sclose);
    Handle set(H5Dcreate2(parent, name, type, space, H5P_DEFAULT, dataset_creation_, H5P_DEFAULT),
               &H5Dclose);
    check(set, name);
    check(H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), name);
  }

  void text(hid_t parent, const char* name, const std::string& value) {
    Handle type(stringType(), &H5Tclose);
    const char* data = value.c_str();
    scalar(parent, name, type, &data);
  }

  void attribute(const char* name, hid_t type, const void* data) {
    Handle space(H5Screate(H5S_SCALAR), &H5Sclose);
    Handle attr(H5Acreate2(handle_, name, type, space, H5P_DEFAULT, H5P_DEFAULT), &H5Aclose);
    check(attr, name);
    check(H5Awrite(attr, type, data), name);
  }

  static hid_t stringType() {
    const hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, H5T_VARIABLE);
    H5Tset_cset(type, H5T_CSET_UTF8);
    return type;
  }

 private:
  void check(long long status, const char* what) const {
    if (status < 0)
      throw Error(SourceLocation{file_.string()}, fmt::format("HDF5 could not write '{}'", what));
  }

  fs::path file_;
  hid_t handle_;
  Handle group_creation_{H5Pcreate(H5P_GROUP_CREATE), &H5Pclose};
  Handle dataset_creation_{H5Pcreate(H5P_DATASET_CREATE), &H5Pclose};
  std::vector<std::unique_ptr<Handle>> groups_;
};

std::vector<double> poses(const std::vector<DatasetGrasp>& grasps, bool closed) {
  std::vector<double> out;
  for (const DatasetGrasp& g : grasps) {
    const Eigen::Matrix<double, 4, 4, Eigen::RowMajor> m = (closed ? g.grasp : g.pregrasp).matrix();
    out.insert(out.end(), m.data(), m.data() + 16);
  }
  return out;
}

// The directions validation turns the weight along, in order (dynamics/grasp_validation.hpp).
const std::vector<double>& validationDirections() {
  static const std::vector<double> directions = {1, 0,  0, -1, 0, 0, 0, 1, 0,
                                                 0, -1, 0, 0,  0, 1, 0, 0, -1};
  return directions;
}

void writeFile(const GraspDataset& dataset, const fs::path& file, hid_t handle) {
  Writer w(file, handle);
  const auto& grasps = dataset.grasps;
  const hsize_t n = grasps.size();
  const hsize_t dofs = grasps.empty() ? 0 : grasps.front().openDofs.size();
  for (const DatasetGrasp& g : grasps)
    if (g.openDofs.size() != dofs || g.closedDofs.size() != dofs)
      throw Error(SourceLocation{file.string()}, "the grasps disagree on the hand's DOF count");

  const int schema = kSchemaVersion;
  w.attribute("schema_version", H5T_NATIVE_INT, &schema);
  Handle string_type(Writer::stringType(), &H5Tclose);
  const char* version = dataset.engineVersion.c_str();
  w.attribute("engine_version", string_type, &version);
  const char* units = "mm";
  w.attribute("units", string_type, &units);
  w.attribute("seed", H5T_NATIVE_UINT64, &dataset.seed);

  const fs::path folder = file.parent_path();
  const hid_t object = w.group(handle, "object");
  w.text(object, "file",
         dataset.objectFile.empty() ? "" : fileReference(dataset.objectFile, folder));
  w.text(object, "name", dataset.objectName);
  w.scalar(object, "mass", H5T_NATIVE_DOUBLE, &dataset.objectMass);
  const hid_t hand = w.group(handle, "hand");
  w.text(hand, "file", dataset.handFile.empty() ? "" : fileReference(dataset.handFile, folder));
  w.text(hand, "name", dataset.handName);

  const hid_t root = w.group(handle, "grasps");
  w.array(root, "transforms", H5T_NATIVE_DOUBLE, {n, 4, 4}, poses(grasps, true).data());
  w.array(root, "pregrasp_transforms", H5T_NATIVE_DOUBLE, {n, 4, 4}, poses(grasps, false).data());
  const hid_t dof_group = w.group(root, "dofs");
  std::vector<double> open, closed;
  for (const DatasetGrasp& g : grasps) {
    open.insert(open.end(), g.openDofs.begin(), g.openDofs.end());
    closed.insert(closed.end(), g.closedDofs.begin(), g.closedDofs.end());
  }
  w.array(dof_group, "open", H5T_NATIVE_DOUBLE, {n, dofs}, open.data());
  w.array(dof_group, "closed", H5T_NATIVE_DOUBLE, {n, dofs}, closed.data());

  hsize_t joints = 0;
  for (const DatasetGrasp& g : grasps) joints = std::max<hsize_t>(joints, g.breakaway.size());
  std::vector<std::uint8_t> engaged;
  std::vector<double> broke_at;
  for (const DatasetGrasp& g : grasps) {
    if (!g.breakaway.empty() && g.breakaway.size() != joints)
      throw Error(SourceLocation{file.string()}, "the grasps disagree on the hand's joint count");
    for (hsize_t j = 0; j < joints; ++j) {
      const BreakawayState state = g.breakaway.empty() ? BreakawayState{} : g.breakaway[j];
      engaged.push_back(state.engaged ? 1 : 0);
      broke_at.push_back(state.value);
    }
  }
  const hid_t breakaway = w.group(root, "breakaway");
  w.array(breakaway, "engaged", H5T_NATIVE_UINT8, {n, joints}, engaged.data());
  w.array(breakaway, "values", H5T_NATIVE_DOUBLE, {n, joints}, broke_at.data());

  const hid_t qualities = w.group(root, "qualities");
  std::vector<double> epsilon, volume;
  std::vector<std::uint8_t> force_closure;
  std::vector<std::int8_t> held;
  for (const DatasetGrasp& g : grasps) {
    epsilon.push_back(g.epsilon);
    volume.push_back(g.volume);
    force_closure.push_back(g.forceClosure ? 1 : 0);
    held.push_back(static_cast<std::int8_t>(g.held));
  }
  w.array(qualities, "epsilon", H5T_NATIVE_DOUBLE, {n}, epsilon.data());
  w.array(qualities, "volume", H5T_NATIVE_DOUBLE, {n}, volume.data());
  w.array(qualities, "force_closure", H5T_NATIVE_UINT8, {n}, force_closure.data());
  w.array(qualities, "held", H5T_NATIVE_INT8, {n}, held.data());

  // Every grasp has 6 rows: an unvalidated grasp's are held -1 and zeros.
  std::vector<std::int8_t> direction_held;
  std::vector<std::uint8_t> direction_failed;
  std::vector<double> slip, turn, seconds;
  for (const DatasetGrasp& g : grasps) {
    if (!g.validation.empty() && g.validation.size() != kDirections)
      throw Error(
          SourceLocation{file.string()},
          fmt::format("a grasp's validation has {} directions, not 6", g.validation.size()));
    if (!g.validation.empty() && std::none_of(g.validation.begin(), g.validation.end(),
                                              [](const DatasetDirection& d) { return d.tried; }))
      throw Error(SourceLocation{file.string()},
                  "a grasp's validation has no direction tried: it would read back as none");
    for (std::size_t k = 0; k < kDirections; ++k) {
      const DatasetDirection d = g.validation.empty() ? DatasetDirection{} : g.validation[k];
      direction_held.push_back(g.validation.empty() || !d.tried ? -1 : d.held ? 1 : 0);
      direction_failed.push_back(d.failed ? 1 : 0);
      slip.push_back(d.slip);
      turn.push_back(d.turn);
      seconds.push_back(d.seconds);
    }
  }
  const hid_t validation = w.group(root, "validation");
  w.array(validation, "directions", H5T_NATIVE_DOUBLE, {kDirections, 3},
          validationDirections().data());
  w.array(validation, "held", H5T_NATIVE_INT8, {n, kDirections}, direction_held.data());
  w.array(validation, "failed", H5T_NATIVE_UINT8, {n, kDirections}, direction_failed.data());
  w.array(validation, "slip", H5T_NATIVE_DOUBLE, {n, kDirections}, slip.data());
  w.array(validation, "turn", H5T_NATIVE_DOUBLE, {n, kDirections}, turn.data());
  w.array(validation, "seconds", H5T_NATIVE_DOUBLE, {n, kDirections}, seconds.data());

  const hid_t contacts = w.group(root, "contacts");
  std::vector<std::uint64_t> offsets{0};
  std::vector<double> points, normals;
  for (const DatasetGrasp& g : grasps) {
    if (g.contactPoints.size() != g.contactNormals.size())
      throw Error(SourceLocation{file.string()}, "a grasp has unequal contact points and normals");
    for (std::size_t k = 0; k < g.contactPoints.size(); ++k) {
      points.insert(points.end(), g.contactPoints[k].data(), g.contactPoints[k].data() + 3);
      normals.insert(normals.end(), g.contactNormals[k].data(), g.contactNormals[k].data() + 3);
    }
    offsets.push_back(offsets.back() + g.contactPoints.size());
  }
  w.array(contacts, "offsets", H5T_NATIVE_UINT64, {n + 1}, offsets.data());
  w.array(contacts, "points", H5T_NATIVE_DOUBLE, {offsets.back(), 3}, points.data());
  w.array(contacts, "normals", H5T_NATIVE_DOUBLE, {offsets.back(), 3}, normals.data());
}

// Reads a dataset file that may have been written by anyone, so libhdf5 is never let to reach
// past the file's own bytes: every link on a path must be a hard link (an external link opens
// another file), no dataset may keep its data in other files (external raw storage, virtual
// datasets), no filter plugin is loaded, and every array's size is checked before memory is
// taken for it (an unfiltered array must hold its bytes in the file; the whole read never takes
// more than an input file may hold). Values must be finite.
class Reader {
 public:
  Reader(const fs::path& file, hid_t handle) : file_(file), handle_(handle) {}

  // The dataset at `path`, its shape checked against `shape` (0: any length), read as `type`.
  template <class T>
  std::vector<T> array(const char* path, hid_t type, std::vector<hsize_t> shape) {
    Handle set = open(path);
    Handle space(H5Dget_space(set), &H5Sclose);
    const int rank = H5Sget_simple_extent_ndims(space);
    if (rank < 0 || rank > 8) fail(path, "has an unreadable shape");
    std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
    H5Sget_simple_extent_dims(space, dims.data(), nullptr);
    if (dims.size() != shape.size()) fail(path, fmt::format("has {} dimensions", dims.size()));
    hsize_t count = 1;
    for (std::size_t k = 0; k < dims.size(); ++k) {
      if (shape[k] != 0 && dims[k] != shape[k])
        fail(path, fmt::format("has {} rows along dimension {}, not {}", dims[k], k, shape[k]));
      if (dims[k] != 0 && count > kMaxInputFileBytes / dims[k])
        fail(path, "is larger than a dataset file may hold");
      count *= dims[k];
    }
    if (H5Sget_simple_extent_type(space) == H5S_NULL) count = 0;
    take(path, set, count, sizeof(T));
    std::vector<T> data(count);
    if (count > 0 && H5Dread(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()) < 0)
      fail(path, "cannot be read");
    if constexpr (std::is_floating_point_v<T>) {
      for (const T value : data)
        if (!std::isfinite(value)) fail(path, "holds a value that is not a finite number");
    }
    last_dims_ = dims;
    return data;
  }

  // Whether a dataset or attribute of `file_type` over `space` holds exactly one variable-length
  // string (what the writer stores; an array of strings would overrun the one pointer read).
  static bool oneString(hid_t file_type, hid_t space) {
    return H5Tget_class(file_type) == H5T_STRING && H5Tis_variable_str(file_type) > 0 &&
           H5Sget_simple_extent_npoints(space) == 1;
  }

  std::string text(const char* path) {
    Handle set = open(path);
    Handle file_type(H5Dget_type(set), &H5Tclose);
    Handle space(H5Dget_space(set), &H5Sclose);
    if (!oneString(file_type, space)) fail(path, "is not one variable-length string");
    Handle type(Writer::stringType(), &H5Tclose);
    char* value = nullptr;
    if (H5Dread(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, &value) < 0 || !value)
      fail(path, "is not a string");
    std::string out(value);
    H5Dvlen_reclaim(type, space, H5P_DEFAULT, &value);
    return out;
  }

  double number(const char* path) { return array<double>(path, H5T_NATIVE_DOUBLE, {}).at(0); }

  // A root attribute holding one number of the class `kind` (integer or float).
  template <class T>
  T attribute(const char* name, hid_t type, H5T_class_t kind) {
    Handle attr = openAttribute(name);
    Handle file_type(H5Aget_type(attr), &H5Tclose);
    Handle space(H5Aget_space(attr), &H5Sclose);
    if (H5Tget_class(file_type) != kind || H5Sget_simple_extent_npoints(space) != 1)
      fail(name, "is not one number");
    T value{};
    if (H5Aread(attr, type, &value) < 0) fail(name, "cannot be read");
    return value;
  }

  std::string textAttribute(const char* name) {
    Handle attr = openAttribute(name);
    Handle file_type(H5Aget_type(attr), &H5Tclose);
    Handle space(H5Aget_space(attr), &H5Sclose);
    if (!oneString(file_type, space)) fail(name, "is not one variable-length string");
    Handle type(Writer::stringType(), &H5Tclose);
    char* value = nullptr;
    if (H5Aread(attr, type, &value) < 0 || !value) fail(name, "is not a string");
    std::string out(value);
    H5free_memory(value);
    return out;
  }

  const std::vector<hsize_t>& lastDims() const { return last_dims_; }

  [[noreturn]] void fail(const char* path, const std::string& what) const {
    throw Error(SourceLocation{file_.string(), 0, path}, fmt::format("'{}' {}", path, what));
  }

 private:
  // Opens the dataset at the absolute `path` after checking that each step of the path is a
  // hard link and that the dataset keeps its data inside this file.
  Handle open(const char* path) {
    std::string prefix;
    for (const char* c = path + 1;; ++c) {
      if (*c != '/' && *c != '\0') continue;
      prefix.assign(path, c);
      if (H5Lexists(handle_, prefix.c_str(), H5P_DEFAULT) <= 0) fail(path, "is missing");
      H5L_info_t link{};
      if (H5Lget_info(handle_, prefix.c_str(), &link, H5P_DEFAULT) < 0 ||
          link.type != H5L_TYPE_HARD)
        fail(path, fmt::format("is reached through '{}', which is not a hard link (external "
                               "and soft links are refused)",
                               prefix));
      if (*c == '\0') break;
    }
    Handle set(H5Dopen2(handle_, path, H5P_DEFAULT), &H5Dclose);
    if (!set.valid()) fail(path, "is not a dataset");
    Handle creation(H5Dget_create_plist(set), &H5Pclose);
    if (!creation.valid() || H5Pget_layout(creation) == H5D_VIRTUAL)
      fail(path, "is a virtual dataset (data in other files is never read)");
    if (H5Pget_external_count(creation) != 0)
      fail(path, "keeps its data in external files (never read)");
    filtered_ = H5Pget_nfilters(creation) > 0;
    return set;
  }

  Handle openAttribute(const char* name) {
    if (H5Aexists(handle_, name) <= 0) fail(name, "(an attribute of the file) is missing");
    Handle attr(H5Aopen(handle_, name, H5P_DEFAULT), &H5Aclose);
    if (!attr.valid()) fail(name, "cannot be opened");
    return attr;
  }

  // Counts `count` elements of `size` bytes against the read's budget. An unfiltered dataset
  // must store its bytes: a sparse one (a few KB declaring gigabytes) is refused.
  void take(const char* path, hid_t set, hsize_t count, std::size_t size) {
    if (count == 0) return;
    Handle file_type(H5Dget_type(set), &H5Tclose);
    const std::size_t stored = H5Tget_size(file_type);
    if (!filtered_ && H5Dget_storage_size(set) < count * stored)
      fail(path, "declares more values than the file stores");
    const hsize_t bytes = count * std::max(size, stored);
    if (bytes > kMaxInputFileBytes - taken_)
      fail(path, fmt::format("would take more than the {} bytes a dataset file may hold",
                             kMaxInputFileBytes));
    taken_ += bytes;
  }

  fs::path file_;
  hid_t handle_;
  std::vector<hsize_t> last_dims_;
  bool filtered_ = false;
  hsize_t taken_ = 0;
};

// Grasp i's pose from rows of 4 x 4 matrices; a matrix that is not a rigid motion (a rotation
// and a translation) is refused rather than silently used.
Transform poseAt(const Reader& r, const char* path, const std::vector<double>& values,
                 std::size_t i) {
  Eigen::Matrix<double, 4, 4, Eigen::RowMajor> m;
  std::copy(values.begin() + static_cast<long>(16 * i),
            values.begin() + static_cast<long>(16 * i + 16), m.data());
  const Matrix3 rotation = m.topLeftCorner<3, 3>();
  constexpr double kTolerance = 1e-6;
  if (!(m.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).isZero(0.0) ||
      !(rotation.transpose() * rotation - Matrix3::Identity()).isZero(kTolerance) ||
      rotation.determinant() < 0.0)
    r.fail(path, fmt::format("holds a matrix that is not a rigid motion (grasp {})", i));
  Transform pose;
  pose.matrix() = m;
  return pose;
}

GraspDataset readFile(const fs::path& file, hid_t handle) {
  Reader r(file, handle);
  const int schema = r.attribute<int>("schema_version", H5T_NATIVE_INT, H5T_INTEGER);
  if (schema < kOldestSchemaVersion || schema > kSchemaVersion)
    r.fail("schema_version", fmt::format("is {}; this graspkit reads {} to {}", schema,
                                         kOldestSchemaVersion, kSchemaVersion));
  // Since schema 2 the files are named relative to the dataset's folder (or absolutely).
  const fs::path folder = fs::absolute(file).parent_path();
  auto named = [&](const std::string& stored) {
    if (schema < 2 || stored.empty()) return stored;
    return (folder / stored).lexically_normal().string();
  };
  GraspDataset dataset;
  dataset.engineVersion = r.textAttribute("engine_version");
  dataset.seed = r.attribute<std::uint64_t>("seed", H5T_NATIVE_UINT64, H5T_INTEGER);
  dataset.objectFile = named(r.text("/object/file"));
  dataset.objectName = r.text("/object/name");
  dataset.objectMass = r.number("/object/mass");
  dataset.handFile = named(r.text("/hand/file"));
  dataset.handName = r.text("/hand/name");

  const auto closed_poses = r.array<double>("/grasps/transforms", H5T_NATIVE_DOUBLE, {0, 4, 4});
  const hsize_t n = r.lastDims()[0];
  const auto open_poses =
      r.array<double>("/grasps/pregrasp_transforms", H5T_NATIVE_DOUBLE, {n, 4, 4});
  const auto open = r.array<double>("/grasps/dofs/open", H5T_NATIVE_DOUBLE, {n, 0});
  const hsize_t dofs = r.lastDims()[1];
  const auto closed = r.array<double>("/grasps/dofs/closed", H5T_NATIVE_DOUBLE, {n, dofs});
  const auto engaged = r.array<std::uint8_t>("/grasps/breakaway/engaged", H5T_NATIVE_UINT8, {n, 0});
  const hsize_t joints = r.lastDims()[1];
  const auto broke_at = r.array<double>("/grasps/breakaway/values", H5T_NATIVE_DOUBLE, {n, joints});
  const auto epsilon = r.array<double>("/grasps/qualities/epsilon", H5T_NATIVE_DOUBLE, {n});
  const auto volume = r.array<double>("/grasps/qualities/volume", H5T_NATIVE_DOUBLE, {n});
  const auto force_closure =
      r.array<std::uint8_t>("/grasps/qualities/force_closure", H5T_NATIVE_UINT8, {n});
  const auto held = r.array<std::int8_t>("/grasps/qualities/held", H5T_NATIVE_INT8, {n});
  std::vector<double> directions, slip, turn, seconds;
  std::vector<std::int8_t> direction_held;
  std::vector<std::uint8_t> direction_failed;
  if (schema >= 2) {
    directions = r.array<double>("/grasps/validation/directions", H5T_NATIVE_DOUBLE, {6, 3});
    for (const double value : directions)
      if (std::abs(value) > 1.0) r.fail("/grasps/validation/directions", "is not unit vectors");
    direction_held =
        r.array<std::int8_t>("/grasps/validation/held", H5T_NATIVE_INT8, {n, kDirections});
    direction_failed =
        r.array<std::uint8_t>("/grasps/validation/failed", H5T_NATIVE_UINT8, {n, kDirections});
    slip = r.array<double>("/grasps/validation/slip", H5T_NATIVE_DOUBLE, {n, kDirections});
    turn = r.array<double>("/grasps/validation/turn", H5T_NATIVE_DOUBLE, {n, kDirections});
    seconds = r.array<double>("/grasps/validation/seconds", H5T_NATIVE_DOUBLE, {n, kDirections});
  }
  const auto offsets =
      r.array<std::uint64_t>("/grasps/contacts/offsets", H5T_NATIVE_UINT64, {n + 1});
  const hsize_t m = offsets.back();
  const auto points = r.array<double>("/grasps/contacts/points", H5T_NATIVE_DOUBLE, {m, 3});
  const auto normals = r.array<double>("/grasps/contacts/normals", H5T_NATIVE_DOUBLE, {m, 3});
  for (std::size_t i = 0; i < n; ++i) {
    if (offsets[i] > offsets[i + 1] || offsets[i + 1] > m)
      r.fail("/grasps/contacts/offsets", "is not increasing within the contacts");
    DatasetGrasp g;
    g.grasp = poseAt(r, "/grasps/transforms", closed_poses, i);
    g.pregrasp = poseAt(r, "/grasps/pregrasp_transforms", open_poses, i);
    g.openDofs.assign(open.begin() + static_cast<long>(i * dofs),
                      open.begin() + static_cast<long>((i + 1) * dofs));
    g.closedDofs.assign(closed.begin() + static_cast<long>(i * dofs),
                        closed.begin() + static_cast<long>((i + 1) * dofs));
    for (hsize_t j = 0; j < joints; ++j)
      g.breakaway.push_back({engaged[i * joints + j] != 0, broke_at[i * joints + j]});
    g.epsilon = epsilon[i];
    g.volume = volume[i];
    g.forceClosure = force_closure[i] != 0;
    if (held[i] < -1 || held[i] > 1)
      r.fail("/grasps/qualities/held", "holds a value not -1, 0 or 1");
    g.held = held[i];
    bool validated = false;  // schema 1 has no directions
    if (schema >= 2) {
      const auto row = direction_held.begin() + static_cast<long>(i * kDirections);
      validated = schema == 2 ? *row != -1
                              : std::any_of(row, row + kDirections,
                                            [](std::int8_t direction) { return direction != -1; });
    }
    if (validated) {
      for (std::size_t k = 0; k < kDirections; ++k) {
        const std::size_t at = i * kDirections + k;
        // Schema 2 tried every direction; since schema 3 any may be left untried.
        const bool untried = schema >= 3 && direction_held[at] == -1;
        if (direction_held[at] != 0 && direction_held[at] != 1 && !untried)
          r.fail("/grasps/validation/held",
                 fmt::format("holds {} for grasp {}, direction {}: a validated grasp's "
                             "directions are 0 or 1{}",
                             direction_held[at], i, k, schema >= 3 ? ", or -1 (not tried)" : ""));
        DatasetDirection d;
        d.direction = Vector3(directions[3 * k], directions[3 * k + 1], directions[3 * k + 2]);
        d.tried = !untried;
        d.held = direction_held[at] == 1;
        d.failed = direction_failed[at] != 0;
        d.slip = slip[at];
        d.turn = turn[at];
        d.seconds = seconds[at];
        g.validation.push_back(d);
      }
    }
    for (std::uint64_t k = offsets[i]; k < offsets[i + 1]; ++k) {
      g.contactPoints.emplace_back(points[3 * k], points[3 * k + 1], points[3 * k + 2]);
      g.contactNormals.emplace_back(normals[3 * k], normals[3 * k + 1], normals[3 * k + 2]);
    }
    dataset.grasps.push_back(std::move(g));
  }
  return dataset;
}

// A dataset as bytes, to carry it from the child process that read it
// (io/dataset/contained_read.hpp). Both ends are this build, so the values travel as their memory
// images, exactly.
class Packer {
 public:
  template <typename T>
  void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes_.append(reinterpret_cast<const char*>(&value), sizeof value);
  }
  void put(const std::string& text) {
    put(text.size());
    bytes_.append(text);
  }
  template <typename T>
  void put(const std::vector<T>& values) {
    put(values.size());
    for (const T& value : values) put(value);
  }
  template <int Rows, int Cols>
  void put(const Eigen::Matrix<double, Rows, Cols>& m) {
    for (int k = 0; k < Rows * Cols; ++k) put(m.data()[k]);
  }
  void put(const Transform& pose) { put(Eigen::Matrix4d(pose.matrix())); }
  void put(const BreakawayState& state) {
    put(state.engaged);
    put(state.value);
  }
  std::string take() { return std::move(bytes_); }

 private:
  std::string bytes_;
};

class Unpacker {
 public:
  explicit Unpacker(std::string_view bytes) : bytes_(bytes) {}
  template <typename T>
  void get(T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    need(sizeof value);
    std::memcpy(static_cast<void*>(&value), bytes_.data(), sizeof value);
    bytes_.remove_prefix(sizeof value);
  }
  void get(std::string& text) {
    std::size_t size = 0;
    get(size);
    need(size);
    text.assign(bytes_.substr(0, size));
    bytes_.remove_prefix(size);
  }
  template <typename T>
  void get(std::vector<T>& values) {
    std::size_t size = 0;
    get(size);
    need(size);  // each value takes at least a byte
    values.resize(size);
    for (T& value : values) get(value);
  }
  template <int Rows, int Cols>
  void get(Eigen::Matrix<double, Rows, Cols>& m) {
    for (int k = 0; k < Rows * Cols; ++k) get(m.data()[k]);
  }
  void get(Transform& pose) {
    Eigen::Matrix4d m;
    get(m);
    pose.matrix() = m;
  }
  void get(BreakawayState& state) {
    get(state.engaged);
    get(state.value);
  }

 private:
  void need(std::size_t bytes) const {
    if (bytes_.size() < bytes) throw Error("a dataset read in a child process came back cut short");
  }
  std::string_view bytes_;
};

std::string pack(const GraspDataset& d) {
  Packer p;
  p.put(d.objectFile);
  p.put(d.objectName);
  p.put(d.objectMass);
  p.put(d.handFile);
  p.put(d.handName);
  p.put(d.engineVersion);
  p.put(d.seed);
  p.put(d.grasps.size());
  for (const DatasetGrasp& g : d.grasps) {
    p.put(g.pregrasp);
    p.put(g.grasp);
    p.put(g.openDofs);
    p.put(g.closedDofs);
    p.put(g.breakaway);
    p.put(g.epsilon);
    p.put(g.volume);
    p.put(g.forceClosure);
    p.put(g.held);
    p.put(g.validation.size());
    for (const DatasetDirection& d : g.validation) {
      p.put(Eigen::Matrix<double, 3, 1>(d.direction));
      p.put(d.held);
      p.put(d.slip);
      p.put(d.turn);
      p.put(d.seconds);
      p.put(d.failed);
      p.put(d.tried);
    }
    p.put(g.contactPoints);
    p.put(g.contactNormals);
  }
  return p.take();
}

GraspDataset unpack(std::string_view bytes) {
  Unpacker u(bytes);
  GraspDataset d;
  u.get(d.objectFile);
  u.get(d.objectName);
  u.get(d.objectMass);
  u.get(d.handFile);
  u.get(d.handName);
  u.get(d.engineVersion);
  u.get(d.seed);
  std::size_t count = 0;
  u.get(count);
  if (count > bytes.size()) throw Error("a dataset read in a child process came back cut short");
  d.grasps.resize(count);
  for (DatasetGrasp& g : d.grasps) {
    u.get(g.pregrasp);
    u.get(g.grasp);
    u.get(g.openDofs);
    u.get(g.closedDofs);
    u.get(g.breakaway);
    u.get(g.epsilon);
    u.get(g.volume);
    u.get(g.forceClosure);
    u.get(g.held);
    std::size_t directions = 0;
    u.get(directions);
    if (directions > kDirections)
      throw Error("a dataset read in a child process came back malformed");
    g.validation.resize(directions);
    for (DatasetDirection& d : g.validation) {
      Eigen::Matrix<double, 3, 1> direction;
      u.get(direction);
      d.direction = direction;
      u.get(d.held);
      u.get(d.slip);
      u.get(d.turn);
      u.get(d.seconds);
      u.get(d.failed);
      u.get(d.tried);
    }
    u.get(g.contactPoints);
    u.get(g.contactNormals);
  }
  return d;
}

// libhdf5's read of a file's bytes in this process: the child's half of loadGraspDataset.
GraspDataset readImage(const std::string& bytes, const fs::path& file) {
  Handle access(H5Pcreate(H5P_FILE_ACCESS), &H5Pclose);
  if (H5Pset_fapl_core(access, 1 << 16, 0) < 0 ||
      H5Pset_file_image(access, const_cast<char*>(bytes.data()), bytes.size()) < 0)
    throw Error(SourceLocation{file.string()}, "HDF5 cannot hold the file in memory");
  // The core driver refuses an image whose name exists on disk; this name never can.
  Handle handle(H5Fopen("/proc/self/graspkit-dataset-image", H5F_ACC_RDONLY, access), &H5Fclose);
  if (!handle.valid()) throw Error(SourceLocation{file.string()}, "not an HDF5 file");
  return readFile(file, handle);
}

// What the child may take: a dataset's arrays hold up to the 1 GiB of its file, and libhdf5 its
// working copies beside them.
constexpr std::size_t kChildMemory = std::size_t{4} << 30;

// How long the child may read: libhdf5 reads a sound dataset at hundreds of MB/s (a 100-grasp
// file in milliseconds), but a corrupt global heap can make it loop for ever (the fuzz target
// found H5HG_read spinning on a variable-length string attribute). So the bound grows with the
// file: 5 s, and a second more per 32 MiB (37 s for the largest file graspkit reads).
std::chrono::seconds childTime(std::size_t bytes) {
  return std::chrono::seconds{5 + static_cast<long>(bytes >> 25)};
}

}  // namespace

void saveGraspDataset(const GraspDataset& dataset, const fs::path& file) {
  const std::lock_guard lock(hdf5Mutex());
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // errors become graspkit::Error, not stderr
  checkReplaceable(file);
  const fs::path temporary =
      file.parent_path() / fmt::format(".{}.{}.tmp", file.filename().string(), ::getpid());
  try {
    {
      Handle handle(H5Fcreate(temporary.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT),
                    &H5Fclose);
      if (!handle.valid())
        throw Error(SourceLocation{file.string()}, "HDF5 cannot create the file");
      writeFile(dataset, file, handle);
    }
    fs::rename(temporary, file);
  } catch (...) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw;
  }
}

GraspDataset loadGraspDataset(const fs::path& file) {
  // The file's bytes come through the read gate (a host's read policy, a Lua sandbox) and
  // libhdf5 reads them from memory: it never opens the path itself.
  const std::string bytes = readInputFile(file);
  const std::lock_guard lock(hdf5Mutex());
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  H5PLset_loading_state(0);  // a dataset's filter never loads a shared library
  if (bytes.empty()) throw Error(SourceLocation{file.string()}, "not an HDF5 file");
  checkHdf5Image(bytes, file);
  // libhdf5 trusts more of a file than can be checked here: it reads in a child process, and a
  // crash or a runaway there is an error naming the file (io/dataset/contained_read.hpp).
  return unpack(readInChild([&] { return pack(readImage(bytes, file)); }, file,
                            childTime(bytes.size()), kChildMemory));
}

}  // namespace graspkit
