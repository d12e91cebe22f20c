#pragma once
// Internal: checks on an HDF5 file's bytes that libhdf5 does not make before it trusts them.
//
// libhdf5 copies a global-heap object (where variable-length strings live) by the size the
// object's own header gives, without checking that it fits inside its heap collection: a file
// that says "16 MB" for a 5-byte string makes libhdf5 read far past its buffer (found by the
// dataset fuzz target, libhdf5 1.10, H5HG_read). graspkit hands libhdf5 a file only after
// every heap collection in it has been checked.

#include <filesystem>
#include <string_view>

namespace graspkit {

// Throws graspkit::Error naming `file` when the image is not one graspkit can give libhdf5: its
// superblock must sit at the start with 8-byte offsets and lengths (as every HDF5 writer makes
// by default), and every global-heap collection (any "GCOL" signature of version 1: libhdf5
// checks the signature at each collection it loads, so none escapes the scan) must lie inside
// the file with each object inside the collection.
void checkHdf5Image(std::string_view image, const std::filesystem::path& file);

}  // namespace graspkit
