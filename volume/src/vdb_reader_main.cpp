// nimbus-vdb-reader: the program that reads foreign VDB files for nimbus, in a process of its
// own with the limits call_isolated set (vdb_isolated.cpp starts it; base/isolated_call.hpp).
// It opens the file, chooses the grids as the caller asked (vdb_grid_choice.hpp) and answers
// with them (vdb_answer.hpp). A crash, hang or absurd allocation inside OpenVDB ends here.
//
//   nimbus-vdb-reader --isolated-call MEMORY_BYTES FILE one-float|every any|name NAME
#include <malloc.h>
#include <tbb/global_control.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "nimbus/base/isolated_call.hpp"
#include "vdb_answer.hpp"
#include "vdb_common.hpp"
#include "vdb_grid_choice.hpp"
#include "vdb_open.hpp"

int main(int argc, char** argv) {
  using namespace nimbus::volume;
  // One thread and one malloc arena, as reading is serial: every extra thread's stack and arena
  // would take address space from the budget the caller set.
  mallopt(M_ARENA_MAX, 1);
  tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  return nimbus::serve_isolated_call(argc, argv, [](const std::vector<std::string>& args, std::string& out) {
    if (args.empty()) throw std::invalid_argument("no file to read");
    const std::filesystem::path path = args[0];
    const detail::GridRequest request = detail::request_from_words({args.begin() + 1, args.end()});
    try {
      detail::init_openvdb();
      detail::OpenedVdb vdb = detail::open_vdb(path);
      detail::encode_answer(vdb, detail::read_chosen_grids(vdb, path, request), out);
    } catch (const GridNotFound& e) {
      out = detail::grid_not_found_answer(e.what());
    } catch (const std::bad_alloc&) {
      throw;  // reported as the limit it is
    } catch (const std::exception& e) {
      out = detail::error_answer(e.what());
    }
  });
}
