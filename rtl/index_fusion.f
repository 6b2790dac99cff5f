// Kernel 1, index fusion: its sources in compile order. Paths are relative to this file:
// `verilator -F rtl/index_fusion.f` from anywhere, `-f` from rtl/.
saturating_add.sv
spill_register.sv
index_fusion.sv
