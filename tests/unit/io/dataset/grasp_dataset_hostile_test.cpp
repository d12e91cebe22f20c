// Grasp dataset files written by an attacker: libhdf5 can be made to read other files (external
// raw storage, external links, virtual datasets) or to take gigabytes from a few kilobytes.
// Each case starts from a valid file (saved by graspkit), swaps one dataset or attribute for a
// hostile one with libhdf5's own API, and must end in a located graspkit::Error, with the
// secret outside the allowed folder never read, even when no read guard is installed.

#include <gtest/gtest.h>
#include <hdf5.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "graspkit/base/error.hpp"
#include "graspkit/base/input_file.hpp"
#include "graspkit/io/dataset/grasp_dataset_file.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

namespace fs = std::filesystem;

GraspDataset oneGrasp() {
  GraspDataset d;
  d.objectFile = "objects/cylinder.xml";
  d.objectName = "cylinder";
  d.objectMass = 120.0;
  d.handFile = "Barrett.xml";
  d.handName = "Barrett";
  d.engineVersion = "0.1.0";
  DatasetGrasp g;
  g.openDofs = {0, 0, 0, 0};
  g.closedDofs = {0.2, 0.2, 0.2, 0};
  g.epsilon = 0.1;
  g.volume = 0.2;
  d.grasps = {g};
  return d;
}

struct Folders {
  fs::path sandbox;  // where the "script" may read
  fs::path outside;  // where it may not
  fs::path secret;   // a file outside holding bytes the reader must never see
};

Folders makeFolders(const std::string& name) {
  Folders f;
  f.sandbox = test::scratchDir() / (name + "_sandbox");
  f.outside = test::scratchDir() / (name + "_outside");
  fs::create_directories(f.sandbox);
  fs::create_directories(f.outside);
  f.secret = f.outside / "secret.bin";
  std::ofstream(f.secret, std::ios::binary) << std::string(64, 'S');
  return f;
}

// Saves a valid dataset into the sandbox, then lets `tamper` change it through libhdf5.
fs::path hostileFile(const Folders& f, const std::function<void(hid_t)>& tamper) {
  const fs::path file = f.sandbox / "hostile.h5";
  saveGraspDataset(oneGrasp(), file);
  const hid_t h = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  EXPECT_GE(h, 0);
  tamper(h);
  H5Fclose(h);
  return file;
}

// Loads `file` as a sandboxed script would (reads only inside the sandbox) and without any
// guard; both must refuse with an error naming the file and the element.
void expectRefused(const Folders& f, const fs::path& file, const std::string& element) {
  const ReadGuard sandbox = [&](const fs::path& p) {
    const fs::path rel = fs::weakly_canonical(p).lexically_relative(fs::canonical(f.sandbox));
    if (rel.empty() || *rel.begin() == "..")
      throw Error(SourceLocation{p.string()}, "outside the sandbox");
  };
  for (const bool guarded : {true, false}) {
    std::optional<ScopedReadGuard> scope;
    if (guarded) scope.emplace(sandbox);
    try {
      const GraspDataset loaded = loadGraspDataset(file);
      ADD_FAILURE() << "loaded, epsilon " << loaded.grasps.at(0).epsilon;
    } catch (const Error& e) {
      EXPECT_EQ(e.where().file, file.string());
      EXPECT_NE(std::string(e.what()).find(element), std::string::npos) << e.what();
    }
  }
}

void replaceEpsilon(hid_t h, hid_t creation) {
  H5Ldelete(h, "/grasps/qualities/epsilon", H5P_DEFAULT);
  const hsize_t n = 1;
  const hid_t space = H5Screate_simple(1, &n, nullptr);
  const hid_t set = H5Dcreate2(h, "/grasps/qualities/epsilon", H5T_NATIVE_DOUBLE, space,
                               H5P_DEFAULT, creation, H5P_DEFAULT);
  EXPECT_GE(set, 0);
  H5Dclose(set);
  H5Sclose(space);
}

TEST(GraspDatasetHostile, ExternalRawStorageIsNeverRead) {
  const Folders f = makeFolders("external_storage");
  const fs::path file = hostileFile(f, [&](hid_t h) {
    const hid_t creation = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_external(creation, f.secret.c_str(), 0, sizeof(double));
    replaceEpsilon(h, creation);
    H5Pclose(creation);
  });
  expectRefused(f, file, "external files");
}

TEST(GraspDatasetHostile, ExternalLinksAreNeverFollowed) {
  const Folders f = makeFolders("external_link");
  const fs::path other = f.outside / "other.h5";
  saveGraspDataset(oneGrasp(), other);
  const fs::path file = hostileFile(f, [&](hid_t h) {
    H5Ldelete(h, "/grasps/qualities/epsilon", H5P_DEFAULT);
    H5Lcreate_external(other.c_str(), "/grasps/qualities/epsilon", h, "/grasps/qualities/epsilon",
                       H5P_DEFAULT, H5P_DEFAULT);
  });
  expectRefused(f, file, "not a hard link");
  // A whole group taken from the other file is refused the same way.
  const fs::path group_file = hostileFile(f, [&](hid_t h) {
    H5Ldelete(h, "/object", H5P_DEFAULT);
    H5Lcreate_external(other.c_str(), "/object", h, "/object", H5P_DEFAULT, H5P_DEFAULT);
  });
  expectRefused(f, group_file, "'/object'");
}

TEST(GraspDatasetHostile, VirtualDatasetsAreNeverRead) {
  const Folders f = makeFolders("virtual");
  const fs::path other = f.outside / "other.h5";
  saveGraspDataset(oneGrasp(), other);
  const fs::path file = hostileFile(f, [&](hid_t h) {
    const hsize_t n = 1;
    const hid_t source = H5Screate_simple(1, &n, nullptr);
    const hid_t creation = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_virtual(creation, source, other.c_str(), "/grasps/qualities/epsilon", source);
    replaceEpsilon(h, creation);
    H5Pclose(creation);
    H5Sclose(source);
  });
  expectRefused(f, file, "virtual dataset");
}

TEST(GraspDatasetHostile, AnAttributeArrayInPlaceOfANumberIsRefused) {
  const Folders f = makeFolders("attribute_array");
  for (const char* name : {"schema_version", "seed"}) {
    const fs::path file = hostileFile(f, [&](hid_t h) {
      H5Adelete(h, name);
      const hsize_t n = 4096;
      const hid_t space = H5Screate_simple(1, &n, nullptr);
      const hid_t attr = H5Acreate2(h, name, H5T_NATIVE_INT64, space, H5P_DEFAULT, H5P_DEFAULT);
      const std::vector<long long> values(n, 1);
      H5Awrite(attr, H5T_NATIVE_INT64, values.data());
      H5Aclose(attr);
      H5Sclose(space);
    });
    expectRefused(f, file, name);
  }
}

TEST(GraspDatasetHostile, ManyStringsInPlaceOfOneAreRefused) {
  const Folders f = makeFolders("strings");
  const fs::path file = hostileFile(f, [&](hid_t h) {
    H5Ldelete(h, "/object/name", H5P_DEFAULT);
    const hsize_t n = 4096;
    const hid_t space = H5Screate_simple(1, &n, nullptr);
    const hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, H5T_VARIABLE);
    const hid_t set =
        H5Dcreate2(h, "/object/name", type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    const std::vector<const char*> values(n, "x");
    H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
    H5Dclose(set);
    H5Tclose(type);
    H5Sclose(space);
  });
  expectRefused(f, file, "/object/name");
}

// A dataset declared with `dims` whose chunks are never written: a few KB of file.
void replaceSparse(hid_t h, const char* path, std::vector<hsize_t> dims, hid_t type) {
  H5Ldelete(h, path, H5P_DEFAULT);
  const hid_t space = H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
  const hid_t creation = H5Pcreate(H5P_DATASET_CREATE);
  std::vector<hsize_t> chunk(dims.size(), 1);
  H5Pset_chunk(creation, static_cast<int>(chunk.size()), chunk.data());
  const hid_t set = H5Dcreate2(h, path, type, space, H5P_DEFAULT, creation, H5P_DEFAULT);
  EXPECT_GE(set, 0);
  H5Dclose(set);
  H5Pclose(creation);
  H5Sclose(space);
}

TEST(GraspDatasetHostile, ShapesThatWrapOrDeclareGigabytesAreRefused) {
  const Folders f = makeFolders("shapes");
  // 4 x 2^62 bytes: the element count wraps to 0 in 64 bits.
  const fs::path wrap = hostileFile(f, [](hid_t h) {
    replaceSparse(h, "/grasps/breakaway/engaged", {4, hsize_t{1} << 62}, H5T_NATIVE_UINT8);
  });
  expectRefused(f, wrap, "/grasps/breakaway/engaged");
  // 2 x 2^26 doubles (1 GiB) declared in a file of kilobytes.
  const fs::path sparse = hostileFile(f, [](hid_t h) {
    replaceSparse(h, "/grasps/dofs/open", {1, hsize_t{1} << 27}, H5T_NATIVE_DOUBLE);
  });
  EXPECT_LT(fs::file_size(sparse), 100'000u);
  expectRefused(f, sparse, "/grasps/dofs/open");
}

TEST(GraspDatasetHostile, NonFiniteValuesAndBrokenPosesAreRefused) {
  const Folders f = makeFolders("values");
  const fs::path nan = hostileFile(f, [](hid_t h) {
    const hid_t set = H5Dopen2(h, "/grasps/qualities/volume", H5P_DEFAULT);
    const double value = std::nan("");
    H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, &value);
    H5Dclose(set);
  });
  expectRefused(f, nan, "/grasps/qualities/volume");
  const fs::path sheared = hostileFile(f, [](hid_t h) {
    const hid_t set = H5Dopen2(h, "/grasps/transforms", H5P_DEFAULT);
    const double m[16] = {2, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, m);
    H5Dclose(set);
  });
  expectRefused(f, sheared, "/grasps/transforms");
}

// libhdf5 copies a global-heap object (a variable-length string) by the size its header gives;
// the fuzz target found a file whose first string claims 16 MB of a 4 KiB heap, which made
// libhdf5 read past its buffer. The heap is checked before libhdf5 sees the file.
TEST(GraspDatasetHostile, AHeapObjectLargerThanItsHeapIsRefused) {
  const fs::path file = test::scratchDir() / "heap.h5";
  saveGraspDataset(oneGrasp(), file);
  std::string bytes = readInputFile(file);
  const std::size_t heap = bytes.find("GCOL");
  ASSERT_NE(heap, std::string::npos) << "the saved file has no global heap to tamper with";
  // The first object's size field: 16 bytes of collection header, then 8 into the object's.
  const std::uint64_t claimed = 16'711'685;
  std::memcpy(bytes.data() + heap + 16 + 8, &claimed, sizeof claimed);
  const fs::path tampered = test::scratchDir() / "heap_tampered.h5";
  std::ofstream(tampered, std::ios::binary) << bytes;
  try {
    loadGraspDataset(tampered);
    FAIL() << "a heap object larger than its heap loaded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("more than its heap holds"), std::string::npos)
        << e.what();
  }
  // The same bytes untouched load: the check refuses the lie, not the file.
  EXPECT_EQ(loadGraspDataset(file).objectName, "cylinder");
}

TEST(GraspDatasetHostile, TheUntamperedFileStillLoadsInTheSandbox) {
  // The control: the same steps with nothing changed load, guarded, to the saved values.
  const Folders f = makeFolders("control");
  const fs::path file = hostileFile(f, [](hid_t) {});
  const ScopedReadGuard guard([&](const fs::path& p) {
    if (fs::weakly_canonical(p).parent_path() != fs::canonical(f.sandbox))
      throw Error(SourceLocation{p.string()}, "outside the sandbox");
  });
  const GraspDataset loaded = loadGraspDataset(file);
  ASSERT_EQ(loaded.grasps.size(), 1u);
  EXPECT_EQ(loaded.grasps[0].epsilon, 0.1);
  EXPECT_EQ(loaded.grasps[0].closedDofs, oneGrasp().grasps[0].closedDofs);
}

}  // namespace
}  // namespace graspkit
