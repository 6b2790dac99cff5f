// The bundled data folder (data/ of the checkout) for the tests. It lives in one compiled file,
// tests/data_dir.cpp, so that the checkout's absolute path reaches no other test source: those
// then compile to the same object in every clone, and a compiler cache shares them.
#pragma once

namespace intgrid::test {

const char* data_dir();

}  // namespace intgrid::test
