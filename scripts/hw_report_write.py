#!/usr/bin/env python3
# The report of scripts/hw_reports.sh: reads what the script collected in TMP and writes the
# Markdown and JSON reports. Run by the script, as
#   hw_report_write.py TMP MD JSON CPU CORES YOSYS NEXTPNR VERILATOR SEED DATE TIME SECONDS
import glob
import json
import re
import sys

(tmp, md_path, json_path, cpu, cores, v_yosys, v_nextpnr, v_verilator, seed, date, stamp,
 run_seconds) = sys.argv[1:13]

PART = {"family": "iCE40", "device": "HX8K", "package": "ct256", "lut4": 7680, "bram": 32}
NEXTPNR = ("nextpnr-ice40 --hx8k --package ct256 --pcf-allow-unconstrained --timing-allow-fail "
           "--seed %s --freq <target, else 100>" % seed)
# docs/hardware.md's figure for the reference point, shown beside our measurement of it.
QUOTED_REFERENCE = {"fmax_mhz": 93, "lut4": 31}
KERNEL_TITLES = {
    "index_fusion": "Kernel 1: index fusion (S_eps)",
    "sectoral_ism": "Kernel 2: sectoral ISM (integer)",
    "reference": "Reference point: a registered 8-bit saturating adder",
}


def read(path):
    with open(path, encoding="utf-8") as f:
        return f.read()


def stat_cells(text):
    """Cell type -> count of the last `Number of cells` block of a Yosys `stat` (flattened)."""
    blocks = re.split(r"Number of cells:\s+\d+\n", text)
    if len(blocks) < 2:
        raise SystemExit("hw_reports: error: no cell counts in a Yosys stat")
    cells = {}
    for line in blocks[-1].splitlines():
        m = re.match(r"^\s+(\S+)\s+(\d+)\s*$", line)
        if not m:
            break
        cells[m.group(1)] = int(m.group(2))
    return cells


def stat_number(text, what):
    found = re.findall(r"Number of %s:\s+(\d+)" % what, text)
    return int(found[-1]) if found else 0


def ice40_resources(design_dir):
    cells = stat_cells(read(design_dir + "/ice40.stat"))
    lut4 = cells.get("SB_LUT4", 0)
    bram = cells.get("SB_RAM40_4K", 0)
    return {
        "lut4": lut4,
        "carry": cells.get("SB_CARRY", 0),
        "dff": sum(n for t, n in cells.items() if t.startswith("SB_DFF")),
        "bram": bram,
        "lut4_utilisation_percent": round(100.0 * lut4 / PART["lut4"], 2),
        "bram_utilisation_percent": round(100.0 * bram / PART["bram"], 2),
        "cells": dict(sorted(cells.items())),
    }


def generic_resources(design_dir):
    cells = stat_cells(read(design_dir + "/generic.stat"))
    coarse = read(design_dir + "/memories.stat")
    flops = sum(n for t, n in cells.items() if re.search(r"DFF|DLATCH|\$_SR_", t))
    return {
        "cells": sum(cells.values()),
        "flip_flops": flops,
        "gates": sum(cells.values()) - flops,
        "memories_before_mapping": stat_number(coarse, "memories"),
        "memory_bits_before_mapping": stat_number(coarse, "memory bits"),
        "by_type": dict(sorted(cells.items())),
    }


def place_and_route(design_dir, freq):
    log = read(design_dir + "/pnr.log")
    rc = int(read(design_dir + "/pnr.rc").strip())
    fmax = re.findall(r"Max frequency for clock '[^']*': ([\d.]+) MHz", log)
    use = {}
    for m in re.finditer(r"^Info:\s+(\w+):\s+(\d+)/\s*(\d+)\s+\d+%", log, re.M):
        use.setdefault(m.group(1), {"used": int(m.group(2)), "available": int(m.group(3))})
    error = re.search(r"^ERROR: (.*)$", log, re.M)
    placed = rc == 0 and bool(fmax)
    by_seed = None
    sweep = glob.glob(design_dir + "/pnr_seed*.log")
    if placed and sweep:
        runs = [(int(seed), float(fmax[-1]))]
        for path in sweep:
            found = re.findall(r"Max frequency for clock '[^']*': ([\d.]+) MHz", read(path))
            runs.append((int(re.search(r"seed(\d+)\.log$", path).group(1)),
                         float(found[-1]) if found else None))
        runs.sort()
        values = [f for _, f in runs if f is not None]
        by_seed = {"seeds": [s for s, _ in runs], "fmax_mhz": [f for _, f in runs],
                   "min": min(values), "max": max(values)}
    over = {k: v["used"] - v["available"] for k, v in use.items() if v["used"] > v["available"]}
    return {
        "design": "every port registered (timing harness)",
        "constraint_mhz": freq,
        "placed": placed,
        "fmax_mhz": float(fmax[-1]) if placed else None,
        "utilisation": use,
        "over_capacity": over,
        "error": error.group(1).strip() if error else None,
        "fmax_by_seed": by_seed,
    }


# --- Simulation: one parser per kernel's report JSON -------------------------------------------
def fusion_sim(r):
    off, on = r["bp_off"], r["bp_on"]
    return {
        "checked": bool(off["ok"] and on["ok"]),
        "cycles_per_cell": off["cycles_per_cell"],
        "cycles_per_cell_backpressure": on["cycles_per_cell"],
        "latency_cycles": off["latency_cycles"]["mean"],
        "latency_cycles_backpressure": on["latency_cycles"]["mean"],
        "sim_cells_per_s": off["sim_cells_per_s"],
    }


def ism_sim(r):
    cpc, lat = r["cycles_per_cell"], r["streaming_latency_mean"]
    return {
        "checked": bool(r["checked"]),
        "cycles_per_cell": cpc["no_backpressure"],
        "cycles_per_cell_backpressure": cpc["backpressure_50"],
        "latency_cycles": lat["no_backpressure"],
        "latency_cycles_backpressure": lat["backpressure_50"],
        "sim_cells_per_s": r["verilator_cells_per_second"],
    }


SIM = {"index_fusion": fusion_sim, "sectoral_ism": ism_sim}

sim_rows = [json.loads(line) for line in read(tmp + "/sim.jsonl").splitlines() if line.strip()]
for row in sim_rows:
    if row.get("kernel") not in SIM:
        raise SystemExit("hw_reports: error: no parser for the report of kernel %r" % row.get("kernel"))
    SIM[row["kernel"]](row)  # fails here, clearly, if a report's fields changed
failed = [r for r in sim_rows if not SIM[r["kernel"]](r)["checked"]]
if failed:
    raise SystemExit("hw_reports: error: a simulation failed its checks: %s" % json.dumps(failed[0]))


def parse_params(text):
    out = {}
    for item in text.split(","):
        key, value = item.split("=", 1)
        out[key] = int(value) if value.isdigit() else value
    return out


def config_label(params):
    if list(params) == ["config"]:
        return params["config"]
    return " ".join("%s=%s" % kv for kv in params.items())


def sim_of(kernel, params):
    for r in sim_rows:
        if r.get("kernel") == kernel and all(r.get(k) == v for k, v in params.items()):
            return r
    return None


# --- The designs -------------------------------------------------------------------------------
designs = []
for line in read(tmp + "/designs.tsv").splitlines():
    did, kernel, params, top, harness, target, fit = line.split("\t")
    params = parse_params(params)
    d = tmp + "/designs/" + did
    target = None if target == "-" else int(target)
    sim = sim_of(kernel, params)
    designs.append({
        "id": did,
        "kernel": kernel,
        "configuration": config_label(params),
        "parameters": params,
        "top": top,
        "fmax_target_mhz": target,
        "must_fit": fit == "yes",
        "simulation": sim,
        "ice40": ice40_resources(d),
        "place_and_route": place_and_route(d, target or 100),
        "generic": generic_resources(d),
    })


def fmt(x, digits=3):
    if x is None:
        return "n/a"
    if isinstance(x, float):
        return "%.*f" % (digits, x)
    return str(x)


def speed(x):
    return "%.2f M" % (x / 1e6)


def fit_text(d):
    p, r = d["place_and_route"], d["ice40"]
    if p["placed"]:
        io = p["utilisation"].get("SB_IO", {})
        return "fits the HX8K: %d LUT4 (%.1f%%), %d of %d BRAM, %s of %s I/O" % (
            r["lut4"], r["lut4_utilisation_percent"], r["bram"], PART["bram"], io.get("used", "?"),
            io.get("available", "?"))
    if p["over_capacity"]:
        names = {"SB_IO": "I/O", "ICESTORM_LC": "logic cells", "ICESTORM_RAM": "BRAM"}
        over = ", ".join("%d of %d %s (%d over)" % (p["utilisation"][k]["used"],
                                                   p["utilisation"][k]["available"], names.get(k, k), n)
                         for k, n in sorted(p["over_capacity"].items()))
        return "does not fit the HX8K: %s" % over
    return "not placed: %s" % (p["error"] or "see nextpnr's log")


# --- Targets -----------------------------------------------------------------------------------
targets = []
for d in designs:
    name = "%s %s" % (d["kernel"], d["configuration"])
    p = d["place_and_route"]
    if d["fmax_target_mhz"] is not None:
        t = d["fmax_target_mhz"]
        f = p["fmax_mhz"]
        met = f is not None and f >= t
        if f is None:
            how = "not placed"
        elif met:
            how = "margin %+.1f MHz (%+.0f%%)" % (f - t, 100.0 * (f - t) / t)
        else:
            how = "short by %.1f MHz (%.0f%%)" % (t - f, 100.0 * (t - f) / t)
        if p["fmax_by_seed"]:
            b = p["fmax_by_seed"]
            how += "; seeds %d..%d: %.1f..%.1f MHz" % (b["seeds"][0], b["seeds"][-1], b["min"],
                                                      b["max"])
        targets.append({"kernel": d["kernel"], "configuration": d["configuration"],
                        "target": "Fmax >= %d MHz on the HX8K" % t,
                        "measured": "%s MHz" % fmt(f, 1), "met": met, "detail": how})
    if d["must_fit"]:
        targets.append({"kernel": d["kernel"], "configuration": d["configuration"],
                        "target": "fits the HX8K (ct256), placed and routed",
                        "measured": fit_text(d), "met": p["placed"],
                        "detail": "" if p["placed"] else fit_text(d).split(": ", 1)[-1]})
fusion_sims = [r for r in sim_rows if r["kernel"] == "index_fusion"]
if fusion_sims:
    worst = max(r["bp_off"]["steady_ii"] for r in fusion_sims)
    targets.append({"kernel": "index_fusion", "configuration": "all %d simulated" % len(fusion_sims),
                    "target": "one beat per cycle (II = 1), no back-pressure",
                    "measured": "steady-state cycles per beat <= %.5f" % worst,
                    "met": worst <= 1.0 + 1e-9,
                    "detail": "" if worst <= 1.0 + 1e-9 else "II %.5f" % worst})
for r in sim_rows:
    if r["kernel"] != "sectoral_ism":
        continue
    cells, setup = r["cells_per_reading"], r["setup_cycles"]
    cpc = r["cycles_per_cell"]["no_backpressure"]
    targets.append({
        "kernel": "sectoral_ism", "configuration": r["config"],
        "target": "one cell per cycle after the per-reading set-up",
        "measured": "%.3f cycles per cell back to back; set-up %d..%d cycles (mean %.0f) per "
                    "%d-cell reading" % (cpc, setup["min"], setup["max"], setup["mean"], cells),
        "met": None,
        "detail": "not a pass/fail figure of the report: back to back, a reading costs its set-up "
                  "when that is longer than its %d output cycles (set-up and output overlap in "
                  "two banks; SectoralIsmRtl.*FullThroughput checks the bound)" % cells})

# --- Summary rows for `intgrid demo` -----------------------------------------------------------
summary = []
for d in designs:
    if d["kernel"] not in SIM:
        continue
    s = SIM[d["kernel"]](d["simulation"]) if d["simulation"] else {}
    r, p, t = d["ice40"], d["place_and_route"], d["fmax_target_mhz"]
    summary.append({
        "kernel": d["kernel"],
        "configuration": d["configuration"],
        "cycles_per_cell": s.get("cycles_per_cell"),
        "cycles_per_cell_backpressure": s.get("cycles_per_cell_backpressure"),
        "latency_cycles": s.get("latency_cycles"),
        "latency_cycles_backpressure": s.get("latency_cycles_backpressure"),
        "lut4": r["lut4"], "carry": r["carry"], "dff": r["dff"], "bram": r["bram"],
        "fmax_mhz": p["fmax_mhz"],
        "target_mhz": t,
        "target_met": None if t is None else (p["fmax_mhz"] is not None and p["fmax_mhz"] >= t),
        "note": ("%.1f%% of the HX8K's LUT4" % r["lut4_utilisation_percent"]) if p["placed"]
                else fit_text(d),
    })

report = {
    "report": "intgrid hardware kernels (docs/hardware.md, What each kernel reports)",
    "generated_by": "bash scripts/hw_reports.sh",
    "date": date,
    "generated_at": stamp,
    "run_seconds": int(run_seconds),
    "machine": {"cpu": cpu, "cores": int(cores)},
    "tools": {"yosys": v_yosys, "nextpnr_ice40": v_nextpnr, "verilator": v_verilator},
    "part": dict(PART, nextpnr=NEXTPNR, seed=int(seed)),
    "targets": targets,
    "summary": summary,
    "simulation": sim_rows,
    "designs": designs,
}

# --- Markdown ----------------------------------------------------------------------------------
md = []
w = md.append
w("# Hardware report")
w("")
w("Generated by `bash scripts/hw_reports.sh` on %s (%s s) on an `%s`, %s cores; %s, %s, %s. "
  "Every figure below is measured by that run: cycles and latency in Verilator simulation "
  "(the testbenches' report modes, every output checked against golden), resources by Yosys, "
  "Fmax by nextpnr-ice40. Only the targets (and the reference point's figure in docs/hardware.md) "
  "are quoted. Apart from the date, the run time and the simulation speeds, a rerun gives the "
  "same file." % (date, run_seconds, cpu, cores, v_yosys, v_nextpnr, v_verilator))
w("")
w("Part: Lattice %s %s, %s package (%d LUT4, %d SB_RAM40_4K). `%s`, on the kernel with a "
  "register on every port, so that Fmax covers every path of the kernel." % (
      PART["family"], PART["device"], PART["package"], PART["lut4"], PART["bram"], NEXTPNR))
w("")
w("## Targets")
w("")
w("| kernel | configuration | target | measured | met |")
w("|---|---|---|---|---|")
for t in targets:
    verdict = "—" if t["met"] is None else ("yes" if t["met"] else "**no**")
    if t["detail"]:
        verdict += ": " + t["detail"]
    w("| %s | %s | %s | %s | %s |" % (t["kernel"], t["configuration"], t["target"], t["measured"],
                                       verdict))
w("")
w("## Summary")
w("")
w("| kernel | configuration | cycles/cell | latency (cycles) | cycles/cell, back-pressure | "
  "latency, back-pressure | LUT4 | carry | DFF | BRAM | Fmax (MHz) | target (MHz) |")
w("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
for s in summary:
    w("| %s | %s | %s | %s | %s | %s | %d | %d | %d | %d | %s | %s |" % (
        s["kernel"], s["configuration"], fmt(s["cycles_per_cell"]), fmt(s["latency_cycles"], 2),
        fmt(s["cycles_per_cell_backpressure"]), fmt(s["latency_cycles_backpressure"], 2),
        s["lut4"], s["carry"], s["dff"], s["bram"], fmt(s["fmax_mhz"], 1),
        fmt(s["target_mhz"])))
w("")
w("Back-pressure: y_ready high in 50% of cycles (random). Index fusion: inputs always valid, "
  "latency from a beat's acceptance to its output, mean. Sectoral ISM: readings back to back, "
  "latency from a reading's acceptance to its first cell, mean (queueing behind earlier "
  "readings included).")


def ice40_table(ds):
    w("| configuration | LUT4 | carry | DFF | BRAM | LUT4 of the HX8K | logic cells placed | I/O | "
      "Fmax (MHz) | Fmax, seed sweep (MHz) | nextpnr --freq | fit |")
    w("|---|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---|")
    for d in ds:
        r, p = d["ice40"], d["place_and_route"]
        lc = p["utilisation"].get("ICESTORM_LC", {})
        io = p["utilisation"].get("SB_IO", {})
        b = p["fmax_by_seed"]
        others = "n/a" if not b else "%.1f..%.1f (seeds %d..%d)" % (b["min"], b["max"],
                                                                  b["seeds"][0], b["seeds"][-1])
        w("| %s | %d | %d | %d | %d | %.1f%% | %s | %s | %s | %s | %d | %s |" % (
            d["configuration"], r["lut4"], r["carry"], r["dff"], r["bram"],
            r["lut4_utilisation_percent"], "%s/%s" % (lc.get("used", "?"), lc.get("available", "?")),
            "%s/%s" % (io.get("used", "?"), io.get("available", "?")), fmt(p["fmax_mhz"], 1),
            others, p["constraint_mhz"], "yes" if p["placed"] else "**no**: " + fit_text(d).split(": ", 1)[-1]))
    w("")
    w("LUT4, carry, DFF (every SB_DFF* variant) and BRAM (SB_RAM40_4K): `synth_ice40 -top <top>` "
      "of the kernel itself. Logic cells, I/O and Fmax: nextpnr on the registered-port harness "
      "(its extra flip-flops share logic cells with the LUTs).")
    w("")


def generic_table(ds):
    w("| configuration | cells | flip-flops | gates | memories before mapping (bits) | cell types |")
    w("|---|---:|---:|---:|---|---|")
    for d in ds:
        g = d["generic"]
        types = ", ".join("%s %d" % (t.strip("$_").rstrip("_"), n)
                          for t, n in sorted(g["by_type"].items(), key=lambda kv: (-kv[1], kv[0])))
        w("| %s | %d | %d | %d | %d (%d) | %s |" % (
            d["configuration"], g["cells"], g["flip_flops"], g["gates"],
            g["memories_before_mapping"], g["memory_bits_before_mapping"], types))
    w("")
    w("`synth -flatten -top <top>` (Yosys's generic gate library; memories are mapped to "
      "flip-flops and multiplexers, as plain `synth` does, and counted before that in the "
      "memories column).")
    w("")


for kernel in ["index_fusion", "sectoral_ism", "reference"]:
    ds = [d for d in designs if d["kernel"] == kernel]
    if not ds:
        continue
    w("")
    w("## " + KERNEL_TITLES.get(kernel, kernel))
    w("")
    sims = [r for r in sim_rows if r["kernel"] == kernel]
    if kernel == "index_fusion" and sims:
        w("### Simulation (Verilator, `index_fusion_rtl_test --report`)")
        w("")
        w("%d beats per run, inputs always valid; back-pressure off: y_ready always high; on: "
          "y_ready high in 50%% of cycles." % sims[0]["beats"])
        w("")
        w("| B | LANES | cycles/beat | cycles/cell | steady II | latency min/mean/max | "
          "cycles/cell, back-pressure | latency min/mean/max, back-pressure | "
          "sim cells/s | sim cycles/s |")
        w("|---:|---:|---:|---:|---:|---|---:|---|---:|---:|")
        for r in sims:
            off, on = r["bp_off"], r["bp_on"]
            lat = lambda x: "%d / %.2f / %d" % (x["min"], x["mean"], x["max"])
            w("| %d | %d | %.5f | %.5f | %.5f | %s | %.5f | %s | %s | %s |" % (
                r["B"], r["LANES"], off["cycles_per_beat"], off["cycles_per_cell"],
                off["steady_ii"], lat(off["latency_cycles"]), on["cycles_per_cell"],
                lat(on["latency_cycles"]), speed(off["sim_cells_per_s"]),
                speed(off["sim_cycles_per_s"])))
        w("")
    if kernel == "sectoral_ism" and sims:
        w("### Simulation (Verilator, `sectoral_ism_report`)")
        w("")
        w("%d readings uniform over the grid's reach per run. Set-up and latency of isolated "
          "readings (no back-pressure); cycles per cell and streaming latency with readings back "
          "to back, y_ready always high or high in 50%% of cycles." % sims[0]["readings"])
        w("")
        w("| configuration | cells/reading | set-up min/mean/max | latency min/mean/max | "
          "cycles/cell | cycles/cell, back-pressure | streaming latency | "
          "streaming latency, back-pressure | sim cells/s | sim cycles/s |")
        w("|---|---:|---|---|---:|---:|---:|---:|---:|---:|")
        for r in sims:
            st, la = r["setup_cycles"], r["latency_cycles"]
            w("| %s | %d | %d / %.1f / %d | %d / %.1f / %d | %.3f | %.3f | %.1f | %.1f | %s | %s |" % (
                r["config"], r["cells_per_reading"], st["min"], st["mean"], st["max"], la["min"],
                la["mean"], la["max"], r["cycles_per_cell"]["no_backpressure"],
                r["cycles_per_cell"]["backpressure_50"],
                r["streaming_latency_mean"]["no_backpressure"],
                r["streaming_latency_mean"]["backpressure_50"],
                speed(r["verilator_cells_per_second"]), speed(r["verilator_cycles_per_second"])))
        w("")
    if kernel == "reference":
        d = ds[0]
        w("docs/hardware.md quotes about %d MHz in %d LUT4 for a plain registered 8-bit saturating "
          "adder on the HX8K. Measured here (rtl/saturating_add.sv, B = 8, between an input and "
          "an output register, written by the script): %s MHz in %d LUT4 (+ %d SB_CARRY)." % (
              QUOTED_REFERENCE["fmax_mhz"], QUOTED_REFERENCE["lut4"],
              fmt(d["place_and_route"]["fmax_mhz"], 1), d["ice40"]["lut4"], d["ice40"]["carry"]))
        w("")
    w("### iCE40 HX8K (Yosys synth_ice40, nextpnr-ice40)")
    w("")
    ice40_table(ds)
    w("### Technology-neutral (Yosys generic synth)")
    w("")
    generic_table(ds)

w("## Method")
w("")
w("- Simulation: the Verilator testbenches' report programs in build/full (INTGRID_TB_SEED=%s), "
  "each output checked against golden; the script refuses to report a run that failed its "
  "checks." % seed)
w("- Yosys: every file of rtl/ read with `read_verilog -sv`, the configuration set with "
  "`chparam` (index fusion, the adder) or the committed rtl/config/<config>/sectoral_ism_<config>.ys "
  "(written with the ROM files by `intgrid hw-config`; the text is golden's ism_table_files, "
  "golden/kernel/src/table_export.cpp); then `synth_ice40 -top <top>` and `stat`, and separately `synth -flatten -top <top>` "
  "and `stat`.")
w("- nextpnr: `%s`; Fmax is the last \"Max frequency for clock\" line of its log. The design is "
  "the kernel with every input and output registered (harness written by the script into its "
  "temporary folder), so that paths from and to the package pins do not count as kernel "
  "paths; index fusion's data buses are filled through shift registers from one pin each and its "
  "output folded to one pin through registered parities, so that any lane count fits the "
  "package's pins, as it would inside a design. Fmax moves with the placement seed, so each placed design is also placed with a few "
  "more seeds (the range is shown); the targets are judged on seed 1." % NEXTPNR)
w("")

with open(json_path, "w", encoding="utf-8") as f:
    json.dump(report, f, indent=2)
    f.write("\n")
with open(md_path, "w", encoding="utf-8") as f:
    f.write("\n".join(md))
