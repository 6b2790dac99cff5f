#include "data_dir.hpp"

namespace intgrid::test {

const char* data_dir() {
  return INTGRID_DATA_DIR;
}

}  // namespace intgrid::test
