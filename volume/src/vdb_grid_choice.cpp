// Which grids a read takes (vdb_grid_choice.hpp).
#include "vdb_grid_choice.hpp"

#include <openvdb/openvdb.h>

#include <algorithm>
#include <stdexcept>

#include "vdb_open.hpp"

namespace nimbus::volume::detail {
namespace {

// `wanted` if given, else "density" among the float grids, else the first float grid.
std::vector<std::string> one_float(const std::string& file, const std::optional<std::string>& wanted,
                                   const std::vector<GridInfo>& grids) {
  const std::string float_type = openvdb::typeNameAsString<float>();
  if (wanted) {
    bool found = false, is_float = false;
    for (const GridInfo& g : grids)
      if (g.name == *wanted) {
        found = true;
        is_float |= g.value_type == float_type;
      }
    if (!found) throw GridNotFound(file + ": no grid named '" + *wanted + "' (grids: " + list_grids(grids) + ")");
    if (!is_float)
      throw std::runtime_error(file + ": grid '" + *wanted + "' does not hold float values (grids: " +
                               list_grids(grids) + ")");
    return {*wanted};
  }
  std::string chosen;
  for (const GridInfo& g : grids)
    if (g.value_type == float_type && (chosen.empty() || g.name == "density")) {
      chosen = g.name;
      if (chosen == "density") break;
    }
  if (chosen.empty()) throw std::runtime_error(file + ": no float grid to read (grids: " + list_grids(grids) + ")");
  return {chosen};
}

std::vector<std::string> every(const std::string& file, const std::optional<std::string>& wanted,
                               const std::vector<GridInfo>& grids) {
  if (wanted && std::none_of(grids.begin(), grids.end(), [&](const GridInfo& g) { return g.name == *wanted; }))
    throw GridNotFound(file + ": no grid named '" + *wanted + "' (grids: " + list_grids(grids) + ")");
  std::vector<std::string> names;
  for (const GridInfo& g : grids)
    if (!wanted || g.name == *wanted) names.push_back(g.name);
  return names;
}

}  // namespace

std::vector<std::string> choose_grids(const std::string& file, const GridRequest& request,
                                      const std::vector<GridInfo>& grids) {
  return request.kind == GridRequest::Kind::OneFloat ? one_float(file, request.name, grids)
                                                     : every(file, request.name, grids);
}

openvdb::GridPtrVec read_chosen_grids(OpenedVdb& vdb, const std::filesystem::path& path, const GridRequest& request) {
  openvdb::GridPtrVec read;
  for (const std::string& name : choose_grids(path.string(), request, vdb.grids)) read.push_back(read_grid(vdb, path, name));
  return read;
}

// "one-float" | "every", then "name" NAME or "any".
std::vector<std::string> request_to_words(const GridRequest& request) {
  std::vector<std::string> words{request.kind == GridRequest::Kind::OneFloat ? "one-float" : "every"};
  if (request.name) {
    words.push_back("name");
    words.push_back(*request.name);
  } else {
    words.push_back("any");
  }
  return words;
}

GridRequest request_from_words(const std::vector<std::string>& words) {
  GridRequest r;
  const bool kind_ok = !words.empty() && (words[0] == "one-float" || words[0] == "every");
  const bool name_ok = (words.size() == 2 && words[1] == "any") || (words.size() == 3 && words[1] == "name");
  if (!kind_ok || !name_ok) throw std::invalid_argument("not a grid request");
  r.kind = words[0] == "one-float" ? GridRequest::Kind::OneFloat : GridRequest::Kind::Every;
  if (words.size() == 3) r.name = words[2];
  return r;
}

}  // namespace nimbus::volume::detail
