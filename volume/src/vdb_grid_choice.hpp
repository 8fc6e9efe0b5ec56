// Private: which grids of a VDB file a read takes, as data, so that the isolated reader program
// (vdb_reader_main.cpp) can make the same choice as the caller would: it gets the request on its
// command line and chooses from the file's list itself.
#pragma once
#include <openvdb/openvdb.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "nimbus/volume/vdb_read.hpp"

namespace nimbus::volume::detail {

struct GridRequest {
  enum class Kind {
    OneFloat,  // read_volume_vdb: `name`, else "density" among the float grids, else the first float grid
    Every,     // summarize_vdb: `name` only, else every grid
  };
  Kind kind = Kind::OneFloat;
  std::optional<std::string> name;
};

// The names to read, in order. GridNotFound when `name` is not in the file; std::runtime_error
// (naming `file` and listing its grids) when a float grid is wanted and there is none.
std::vector<std::string> choose_grids(const std::string& file, const GridRequest& request,
                                      const std::vector<GridInfo>& grids);

// The chosen grids of an opened file, read (read_grid's errors).
struct OpenedVdb;
openvdb::GridPtrVec read_chosen_grids(OpenedVdb& vdb, const std::filesystem::path& path, const GridRequest& request);

// The request as command-line words and back (std::invalid_argument on words it did not write).
std::vector<std::string> request_to_words(const GridRequest& request);
GridRequest request_from_words(const std::vector<std::string>& words);

}  // namespace nimbus::volume::detail
