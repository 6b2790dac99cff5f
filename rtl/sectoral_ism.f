// Kernel 2, the sectoral ISM: its sources in compile order (the package first). Paths are
// relative to this file: `verilator -F rtl/sectoral_ism.f` from anywhere, `-f` from rtl/.
// A configuration adds its parameters: -f config/<name>/sectoral_ism_<name>.vc (from rtl/).
sectoral_ism_pkg.sv
sectoral_ism_rom.sv
sdp_ram.sv
spill_register.sv
sectoral_ism_mul.sv
sectoral_ism_density.sv
sectoral_ism_log_add.sv
sectoral_ism_index.sv
sectoral_ism_setup.sv
sectoral_ism_stream.sv
sectoral_ism.sv
