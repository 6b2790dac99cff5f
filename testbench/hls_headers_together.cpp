// Both kernels' headers in one translation unit, compiled with __SYNTHESIS__ defined and -Werror
// (testbench/sectoral_ism.cmake): INTGRID_HLS_PRAGMA has one definition (hls/hls_pragma.hpp), and
// a second, different one in either header would be a macro-redefinition error here.
#ifndef __SYNTHESIS__
#error "hls_headers_together.cpp must be compiled with __SYNTHESIS__ defined"
#endif

#include "hls/index_fusion.hpp"
#include "hls/sectoral_ism.hpp"
