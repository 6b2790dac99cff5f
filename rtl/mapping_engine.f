// The mapping engine: its sources in compile order. Paths are relative to this file:
// `verilator -F rtl/mapping_engine.f` from anywhere, `-f` from rtl/.
saturating_add.sv
sdp_ram.sv
mapping_engine_divider.sv
mapping_engine_sine.sv
mapping_engine.sv
