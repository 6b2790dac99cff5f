// The one definition of INTGRID_HLS_PRAGMA, shared by every kernel in hls/.
//
// INTGRID_HLS_PRAGMA("HLS PIPELINE II=1") becomes `#pragma HLS PIPELINE II=1` when a synthesis
// tool compiles the code (Vitis HLS and Catapult both define __SYNTHESIS__) and nothing
// otherwise, so a plain compiler with -Wall sees no unknown pragma. The text is a string literal
// so that a formatter leaves its spelling alone; the spelling is Vitis HLS's (UG1399): PIPELINE,
// UNROLL, ARRAY_PARTITION, DEPENDENCE, INLINE, INTERFACE. Catapult users map them
// (docs/hardware.md, "What an HLS tool run needs").
#pragma once

#if defined(__SYNTHESIS__)
#define INTGRID_HLS_PRAGMA(text) _Pragma(text)
#else
#define INTGRID_HLS_PRAGMA(text)
#endif
