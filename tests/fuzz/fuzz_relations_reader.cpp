// The benchmark relations reader on any bytes: relations with finite fields, each with the line
// it came from in increasing order, or one InputError naming the file.
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "intgrid/io/relations_io.hpp"

using namespace intgrid;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file =
      fuzz::write_input("input.relations", {reinterpret_cast<const char*>(data), size});
  try {
    const std::vector<io::RelationRecord> records = io::read_relations(file);
    fuzz::require(!records.empty());
    for (std::size_t i = 0; i < records.size(); ++i) {
      const core::Relation& r = records[i].relation;
      fuzz::require(std::isfinite(r.t1) && std::isfinite(r.t2) && std::isfinite(r.motion.x) &&
                    std::isfinite(r.motion.y) && std::isfinite(r.motion.theta));
      fuzz::require(records[i].line >= 1 && (i == 0 || records[i - 1].line < records[i].line));
    }
  } catch (const io::InputError& e) {
    fuzz::check_refusal(e, file);
  }
  return 0;
}
