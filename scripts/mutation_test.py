#!/usr/bin/python3
"""Mutation testing of the hardware kernels (docs/hardware.md, "Mutation testing").

Applies the single-point mutants of a catalogue (testbench/mutants.txt) one at a time to a copy
of the source tree, rebuilds the hardware test targets in one persistent build directory and
runs the hardware tests (ctest -L "hw|formal"). Each mutant is killed (a test failed: the first
failing test is recorded), survived, build-broken (it does not compile: not counted as killed)
or timeout. The working tree itself is never modified.

  scripts/mutation_test.py --list                 check the catalogue against the tree, print it
  scripts/mutation_test.py --only spill.* ism.z_ready.ignores_bank --report docs/mutation.md
  scripts/mutation_test.py --report docs/mutation.md      the whole campaign
  scripts/mutation_test.py --resume --report docs/mutation.md   go on with an interrupted one

Python 3 standard library only.
"""

from __future__ import annotations

import argparse
import dataclasses
import datetime
import fnmatch
import hashlib
import json
import os
import re
import shutil
import signal
import statistics
import subprocess
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
DEFAULT_CATALOGUE = Path("testbench/mutants.txt")
DEFAULT_WORK_DIR = Path("build/mutation")
DEFAULT_LABELS = "hw|formal"
# The catalogue check is labelled hw but reads the tree the mutant was applied to: it would
# "kill" every mutant.
DEFAULT_EXCLUDE = "^mutation_"
# Where the targets of the hardware tests are defined (CMake source directories).
TARGET_DIRS = re.compile(r"(^|/)(testbench|[^/]*formal[^/]*)(/|$)")
# --affected-only builds and tests in stages, cheapest first: the sub-module unit tests, the
# kernels' RTL tests, then every target.
DEFAULT_STAGES = (("sectoral_ism_units_test",), ("index_fusion_rtl_test", "sectoral_ism_rtl_test"))
# Built outside testbench/ but run by hardware tests: `intgrid hw-config` writes the generated
# configuration the generated-configuration tests lint and synthesize.
COMMAND_TARGETS = ("intgrid",)
EXPECTED_KINDS = ("equivalent", "unreachable")
KEYS = ("file", "find", "replace", "what", "expected")


# ------------------------------------------------------------------------------ catalogue


@dataclasses.dataclass
class Mutant:
    id: str
    file: str
    find: str
    replace: str
    what: str
    expected: str | None  # "equivalent: reason" or "unreachable: reason"
    line: int


class CatalogueError(Exception):
    pass


def unescape(value: str, where: str) -> str:
    def sub(m: re.Match[str]) -> str:
        if m.group(1) == "n":
            return "\n"
        if m.group(1) == "\\":
            return "\\"
        raise CatalogueError(f"{where}: unknown escape \\{m.group(1)} (only \\n and \\\\)")

    return re.sub(r"\\(.)", sub, value)


def parse_catalogue(path: Path) -> list[Mutant]:
    """Reads the catalogue; raises CatalogueError listing every malformed entry."""
    errors: list[str] = []
    entries: list[dict] = []
    for number, raw in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        where = f"{path}:{number}"
        line = raw.strip()
        if not line or line.startswith("#"):
            continue
        header = re.fullmatch(r"\[([A-Za-z0-9_.\-]+)\]", line)
        if header:
            entries.append({"id": header.group(1), "line": number})
            continue
        field = re.fullmatch(r"([a-z]+):(.*)", line)
        if not field or not entries:
            errors.append(f"{where}: expected [id] or 'key: value', got {line!r}")
            continue
        key, value = field.group(1), field.group(2).strip()
        entry = entries[-1]
        if key not in KEYS:
            errors.append(f"{where}: unknown key {key!r} (keys: {', '.join(KEYS)})")
        elif key in entry:
            errors.append(f"{where}: {key} given twice in [{entry['id']}]")
        else:
            try:
                entry[key] = unescape(value, where) if key in ("find", "replace") else value
            except CatalogueError as e:
                errors.append(str(e))
    mutants: list[Mutant] = []
    seen: set[str] = set()
    for e in entries:
        where = f"{path}:{e['line']} [{e['id']}]"
        missing = [k for k in ("file", "find", "replace", "what") if k not in e]
        if missing:
            errors.append(f"{where}: missing {', '.join(missing)}")
            continue
        if e["id"] in seen:
            errors.append(f"{where}: duplicate id")
        seen.add(e["id"])
        if not e["find"]:
            errors.append(f"{where}: empty find")
        if e["find"] == e["replace"]:
            errors.append(f"{where}: replace equals find")
        expected = e.get("expected")
        if expected is not None:
            kind, _, reason = expected.partition(":")
            if kind.strip() not in EXPECTED_KINDS or not reason.strip():
                errors.append(f"{where}: expected must be '<{'|'.join(EXPECTED_KINDS)}>: <reason>'")
        mutants.append(Mutant(e["id"], e["file"], e["find"], e["replace"], e["what"], expected,
                              e["line"]))
    if errors:
        raise CatalogueError("\n".join(errors))
    return mutants


def occurrences(text: str, snippet: str) -> int:
    count, at = 0, text.find(snippet)
    while at >= 0:
        count += 1
        at = text.find(snippet, at + 1)
    return count


def check_snippet(root: Path, m: Mutant) -> str | None:
    """None if the mutant applies to the tree at root, else why not."""
    path = root / m.file
    if not path.is_file():
        return f"{m.file}: no such file"
    n = occurrences(path.read_text(encoding="utf-8"), m.find)
    if n != 1:
        return f"{m.file}: the snippet of [{m.id}] occurs {n} times (must be exactly once): {m.find!r}"
    return None


def select(mutants: list[Mutant], patterns: list[str] | None) -> list[Mutant]:
    if not patterns:
        return mutants
    unknown = [p for p in patterns if not any(fnmatch.fnmatchcase(m.id, p) for m in mutants)]
    if unknown:
        raise CatalogueError(f"no mutant matches {', '.join(unknown)}")
    return [m for m in mutants if any(fnmatch.fnmatchcase(m.id, p) for p in patterns)]


# ------------------------------------------------------------------------------ the copy


def run(cmd: list[str], **kw) -> subprocess.CompletedProcess:
    return subprocess.run(cmd, check=True, text=True, capture_output=True, **kw)


COPY_MARK = Path(".mutation-copy")  # marks a directory sync_tree may prune


def sync_tree(source: Path, dest: Path, work: Path) -> int:
    """Makes dest hold the files git sees in source (tracked and untracked-not-ignored, as they
    are in the working tree; nothing under the work directory). Only files whose content
    differs are written, so the build directory rebuilds only what changed. Returns the number
    of files written or removed."""
    if dest.exists() and any(dest.iterdir()) and not (dest / COPY_MARK).exists():
        sys.exit(f"mutation_test: {dest} exists and is not a copy made by this script")
    listing = run(["git", "ls-files", "-z", "-co", "--exclude-standard"], cwd=source).stdout
    wanted = {Path(p) for p in listing.split("\0") if p and (source / p).exists()
              and not (source / p).resolve().is_relative_to(work.resolve())}
    dest.mkdir(parents=True, exist_ok=True)
    (dest / COPY_MARK).touch()
    changed = 0
    for rel in sorted(wanted):
        src, dst = source / rel, dest / rel
        if src.is_symlink():
            target = os.readlink(src)
            if not (dst.is_symlink() and os.readlink(dst) == target):
                if dst.exists() or dst.is_symlink():
                    dst.unlink()
                dst.parent.mkdir(parents=True, exist_ok=True)
                os.symlink(target, dst)
                changed += 1
            continue
        data = src.read_bytes()
        if dst.is_symlink() or not dst.is_file() or dst.read_bytes() != data:
            if dst.is_symlink():
                dst.unlink()
            dst.parent.mkdir(parents=True, exist_ok=True)
            dst.write_bytes(data)  # a fresh mtime: the build sees the change
            shutil.copymode(src, dst)
            changed += 1
    for dirpath, dirnames, filenames in os.walk(dest, topdown=False):
        for name in filenames:
            rel = Path(dirpath, name).relative_to(dest)
            if rel not in wanted and rel != COPY_MARK:
                Path(dirpath, name).unlink()
                changed += 1
        if Path(dirpath) != dest and not os.listdir(dirpath):
            os.rmdir(dirpath)
    return changed


def tree_key(src: Path) -> str:
    """A digest of every file of the copy that can change a test's outcome (all but docs/ and
    Markdown files): --resume goes on only on the copy it was started on."""
    digest = hashlib.sha256()
    for path in sorted(src.rglob("*")):
        rel = path.relative_to(src)
        if (rel == COPY_MARK or rel.parts[0] == "docs" or rel.suffix == ".md"
                or not path.is_file() or path.is_symlink()):
            continue
        digest.update(str(rel).encode() + b"\0" + path.read_bytes() + b"\0")
    return digest.hexdigest()


def full_preset(source: Path, name: str = "full") -> tuple[dict[str, str], str | None]:
    """The cache variables (inherits resolved) and generator of a configure preset."""
    presets = {p["name"]: p for p in
               json.loads((source / "CMakePresets.json").read_text())["configurePresets"]}

    def resolve(n: str) -> tuple[dict[str, str], str | None]:
        p = presets[n]
        cache: dict[str, str] = {}
        generator = None
        parents = p.get("inherits", [])
        for parent in [parents] if isinstance(parents, str) else parents:
            c, g = resolve(parent)
            cache.update(c)
            generator = generator or g
        for k, v in p.get("cacheVariables", {}).items():
            cache[k] = v["value"] if isinstance(v, dict) else str(v)
        return cache, p.get("generator", generator)

    return resolve(name)


def configure(src: Path, build: Path, log: Path, fatal: bool = True) -> bool:
    """(Re)configures the mutation build directory with the full preset's cache variables;
    a reconfigure keeps everything already built. A failure ends the campaign if `fatal`, else
    it is returned."""
    cache, generator = full_preset(src)
    query = build / ".cmake/api/v1/query/codemodel-v2"
    query.parent.mkdir(parents=True, exist_ok=True)
    query.touch()
    cmd = ["cmake", "-S", str(src), "-B", str(build)]
    if not (build / "CMakeCache.txt").exists():
        if generator:
            cmd += ["-G", generator]
        elif shutil.which("ninja"):
            cmd += ["-G", "Ninja"]
    cmd += [f"-D{k}={v}" for k, v in sorted(cache.items())]
    # A mutant changes a few of the files Verilator writes, and restoring it writes the same
    # files again: with ccache (if installed) those compile from its cache.
    if shutil.which("ccache"):
        cmd += ["-DCMAKE_CXX_COMPILER_LAUNCHER=ccache", "-DCMAKE_C_COMPILER_LAUNCHER=ccache"]
    with log.open("w") as out:
        r = subprocess.run(cmd, stdout=out, stderr=subprocess.STDOUT, text=True)
    if r.returncode != 0 and fatal:
        sys.exit(f"mutation_test: configuring {build} failed, see {log}")
    return r.returncode == 0


def hardware_targets(build: Path) -> list[str]:
    """The targets defined in testbench/ (and any *formal* directory), from CMake's file API,
    and the command the configuration generator's tests run (COMMAND_TARGETS)."""
    reply = build / ".cmake/api/v1/reply"
    index = json.loads(sorted(reply.glob("index-*.json"))[-1].read_text())
    model = next(o for o in index["objects"] if o["kind"] == "codemodel")
    config = json.loads((reply / model["jsonFile"]).read_text())["configurations"][0]
    dirs = config["directories"]
    targets = [t["name"] for t in config["targets"]
               if TARGET_DIRS.search(dirs[t["directoryIndex"]]["source"])]
    if not targets:
        sys.exit("mutation_test: no target in testbench/: is INTGRID_BUILD_HW on?")
    return sorted(targets) + list(COMMAND_TARGETS)


# ------------------------------------------------------------------------------ one run

RESULT_LINE = re.compile(
    r"^\s*\d+/\d+\s+Test\s+#\d+:\s+(?P<name>\S+)\s+\.*\s*(?P<status>.*?)\s+(?P<sec>[\d.]+) sec\s*$")


@dataclasses.dataclass
class TestRun:
    status: str  # "passed", "failed", "timeout", "error"
    first_failure: str | None
    first_failure_status: str | None
    passed: list[str]
    seconds: float


def run_logged(cmd: list[str], log: Path, timeout: float | None, cwd: Path | None = None
               ) -> tuple[int | None, float]:
    """Runs cmd with its output in log; returns (exit code or None on timeout, seconds). On a
    timeout the whole process group (ctest and its tests) is stopped."""
    start = time.monotonic()
    with log.open("w") as out:
        proc = subprocess.Popen(cmd, stdout=out, stderr=subprocess.STDOUT, cwd=cwd,
                                start_new_session=True)
        try:
            code: int | None = proc.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            code = None
            for sig, grace in ((signal.SIGTERM, 10), (signal.SIGKILL, None)):
                try:
                    os.killpg(proc.pid, sig)
                except ProcessLookupError:
                    break
                try:
                    proc.wait(timeout=grace)
                    break
                except subprocess.TimeoutExpired:
                    continue
    return code, time.monotonic() - start


def test_programs(args: argparse.Namespace, build: Path) -> dict[str, Path]:
    """The program each selected test runs (its command's first word), by test name."""
    cmd = ["ctest", "--test-dir", str(build), "--show-only=json-v1", "-L", args.labels]
    if args.exclude:
        cmd += ["-E", args.exclude]
    tests = json.loads(run(cmd).stdout)["tests"]
    return {t["name"]: Path((t.get("command") or [""])[0]) for t in tests}


def built_programs(programs: dict[str, Path], build: Path) -> dict[Path, int]:
    """Modification times of the test programs that the build directory produces."""
    stamps = {}
    for path in set(programs.values()):
        if path.is_relative_to(build) and path.exists():
            stamps[path] = path.stat().st_mtime_ns
    return stamps


def affected_tests(programs: dict[str, Path], before: dict[Path, int], build: Path
                   ) -> list[str]:
    """The tests a mutant can change: those whose program was rebuilt, and every test that runs
    an outside tool (Verilator, Yosys, ...), which may read the mutated source itself."""
    after = built_programs(programs, build)
    return sorted(name for name, path in programs.items()
                  if path not in before or after.get(path) != before[path])


def source_tests(programs: dict[str, Path], build: Path) -> list[str]:
    """The quick tests that run an outside tool on the sources themselves (lint, formal): their
    program is not built here, so they see an RTL mutant before anything is rebuilt. Synthesis
    runs are left to the main run (a minute each, and rarely the first to fail)."""
    return sorted(name for name, path in programs.items()
                  if not path.is_relative_to(build) and "synth" not in name)


def run_tests(args: argparse.Namespace, build: Path, log: Path, timeout: float,
              stop_on_failure: bool, only: list[str] | None = None) -> TestRun:
    cmd = ["ctest", "--test-dir", str(build), "-L", args.labels, "-j", str(args.jobs),
           "--timeout", str(int(timeout)), "--no-tests=error"]
    if args.exclude:
        cmd += ["-E", args.exclude]
    if only is not None:
        cmd += ["-R", "^(" + "|".join(re.escape(n) for n in only) + ")$"]
    if stop_on_failure:
        cmd.append("--stop-on-failure")
    code, seconds = run_logged(cmd, log, timeout)
    first = first_status = None
    passed: list[str] = []
    for line in log.read_text(errors="replace").splitlines():
        m = RESULT_LINE.match(line)
        if not m:
            continue
        status = m.group("status").replace("*", "").strip()
        if status == "Passed" or status.startswith("Skipped"):
            passed.append(m.group("name"))
        elif first is None:
            first, first_status = m.group("name"), status
    if code is None:
        return TestRun("timeout", first, first_status, passed, seconds)
    if first is not None:
        kind = "timeout" if first_status and first_status.startswith("Timeout") else "failed"
        return TestRun(kind, first, first_status, passed, seconds)
    return TestRun("passed" if code == 0 else "error", None, None, passed, seconds)


def build_targets(args: argparse.Namespace, build: Path, targets: list[str], log: Path
                  ) -> tuple[bool, float]:
    cmd = ["cmake", "--build", str(build), "-j", str(args.build_jobs), "--target", *targets]
    code, seconds = run_logged(cmd, log, args.build_timeout)
    return code == 0, seconds


def compile_time_check(log: Path, src: Path) -> str | None:
    """The first failed static_assert of a test when every compiler error is one in
    testbench/: the mutant compiled in its own layer and a compile-time test rejected it."""
    errors = re.findall(r"^(\S+?):(\d+):\d+: error: (.*)$", log.read_text(errors="replace"),
                        re.MULTILINE)
    if not errors or any(not msg.startswith("static assertion failed") for _, _, msg in errors):
        return None
    files = [Path(f) for f, _, _ in errors]
    tests = src / "testbench"
    if not all(f.is_relative_to(tests) for f in files):
        return None
    return f"static_assert {files[0].relative_to(src)}:{errors[0][1]}"


def first_error(log: Path) -> str:
    """The compiler's or Verilator's first error line, else the first failed build step."""
    lines = log.read_text(errors="replace").splitlines()
    for pattern in (r"error:|%Error", r"^FAILED:|\*\*\*|[Ee]rror"):
        for line in lines:
            if re.search(pattern, line):
                return line.strip()[:200]
    return "(no error line found)"


# ------------------------------------------------------------------------------ report


def kill_rate(results: list[dict]) -> tuple[int, int]:
    """(detected, mutants that change an output): build-broken mutants and survivors the
    catalogue explains as equivalent or unreachable are not in the denominator; a timeout (a
    hang fails the suite) counts as detected."""
    relevant = [r for r in results if r["result"] in ("killed", "timeout")
                or (r["result"] == "survived" and not r["expected"])]
    detected = [r for r in relevant if r["result"] in ("killed", "timeout")]
    return len(detected), len(relevant)


def md(text: str) -> str:
    return text.replace("|", "\\|")


def write_report(path: Path, results: list[dict], meta: dict, catalogue_size: int) -> None:
    counts = {k: sum(r["result"] == k for r in results)
              for k in ("killed", "survived", "timeout", "build-broken", "error")}
    detected, relevant = kill_rate(results)
    times = [r["seconds"] for r in results]
    lines = [
        "# Mutation testing: last result",
        "",
        "Written by `scripts/mutation_test.py` (docs/hardware.md, \"Mutation testing\"): each "
        f"mutant of `{meta['catalogue']}` applied alone to a copy of the tree, the hardware test "
        f"targets rebuilt, then `ctest -L \"{meta['labels']}\"`"
        + (f", leaving out the tests that match `{meta['exclude']}`" if meta["exclude"] else "")
        + (" (`--affected-only`: per mutant only the tests whose program was rebuilt, and those "
           "that run Verilator, Yosys or another outside tool; for an RTL mutant the lint and "
           "formal ones first, before the rebuild)" if meta.get("affected_only")
           else "") + ".",
        "",
        f"- Source: `{meta['commit']}`{' with local changes' if meta['dirty'] else ''}; run "
        f"{meta['started']} on {meta['host']} (`--jobs {meta['jobs']}`, build `-j "
        f"{meta['build_jobs']}`).",
        f"- Mutants run: {len(results)} of {catalogue_size} in the catalogue"
        + (" (**partial run**)" if len(results) < catalogue_size else "") + ".",
    ]
    if meta.get("baseline_seconds") is not None:
        lines.append(f"- Baseline (unmutated): build {meta['baseline_build_seconds']:.0f} s, "
                     f"{meta['baseline_tests']} tests passed in {meta['baseline_seconds']:.0f} s.")
    if times:
        lines.append(f"- Time per mutant (rebuild and tests): mean {statistics.mean(times):.0f} s, "
                     f"median {statistics.median(times):.0f} s, max {max(times):.0f} s; total "
                     f"{sum(times) / 60:.1f} min.")
    lines += [
        "",
        "| killed | survived | timeout | build-broken | error |",
        "|---:|---:|---:|---:|---:|",
        f"| {counts['killed']} | {counts['survived']} | {counts['timeout']} | "
        f"{counts['build-broken']} | {counts['error']} |",
        "",
        f"**Kill rate over the mutants that change an output: {detected} of {relevant}"
        + (f" ({100.0 * detected / relevant:.1f}%)" if relevant else "") + ".** Not counted: "
        "build-broken mutants, and survivors the catalogue explains as equivalent or "
        "unreachable; a timeout counts as killed (the suite does not finish).",
        "",
        "| id | file | description | result | killing test | time |",
        "|---|---|---|---|---|---:|",
    ]
    for r in results:
        killer = r["killer"] or ""
        if r["killer_status"] and r["killer_status"] != "Failed":
            killer += f" ({r['killer_status']})"
        result = r["result"]
        if r["expected"]:
            result += f" (expected {r['expected'].partition(':')[0]})"
        lines.append(f"| `{r['id']}` | `{r['file']}` | {md(r['what'])} | {result} | "
                     f"{md(killer)} | {r['seconds']:.0f} s |")
    survivors = [r for r in results if r["result"] == "survived"]
    lines += ["", "## Survivors", ""]
    if not survivors:
        lines.append("None.")
    for r in survivors:
        reason = (f"Expected {r['expected'].partition(':')[0]}: "
                  f"{r['expected'].partition(':')[2].strip()}"
                  if r["expected"] else "**not explained in the catalogue: a gap in the tests**")
        lines.append(f"- `{r['id']}` ({r['file']}): {r['what']}. {reason}.")
    contradicted = [r for r in results if r["expected"] and r["result"] in ("killed", "timeout")]
    if contradicted:
        lines += ["", "Killed although the catalogue expects no observable effect (its note is "
                  "wrong, or a test looks at more than the outputs):", ""]
        lines += [f"- `{r['id']}`: killed by {r['killer']}." for r in contradicted]
    broken = [r for r in results if r["result"] in ("build-broken", "error")]
    if broken:
        lines += ["", "## Build-broken and errors", ""]
        lines += [f"- `{r['id']}` ({r['result']}): `{md(r['detail'])}`" for r in broken]
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(path.suffix + ".tmp")
    tmp.write_text("\n".join(lines) + "\n", encoding="utf-8")
    tmp.replace(path)


# ------------------------------------------------------------------------------ main


def list_catalogue(mutants: list[Mutant], root: Path) -> int:
    problems = [p for p in (check_snippet(root, m) for m in mutants) if p]
    width = max(len(m.id) for m in mutants)
    for m in mutants:
        note = f"  [expected {m.expected.partition(':')[0]}]" if m.expected else ""
        print(f"{m.id:<{width}}  {m.file:<32} {m.what}{note}")
    per_file: dict[str, int] = {}
    for m in mutants:
        per_file[m.file] = per_file.get(m.file, 0) + 1
    print(f"\n{len(mutants)} mutants:")
    for f, n in sorted(per_file.items()):
        print(f"  {n:3d}  {f}")
    for p in problems:
        print(f"error: {p}", file=sys.stderr)
    if problems:
        print(f"{len(problems)} of {len(mutants)} mutants do not apply to {root}", file=sys.stderr)
    return 1 if problems else 0


def git_state(source: Path) -> tuple[str, bool]:
    try:
        commit = run(["git", "rev-parse", "--short=12", "HEAD"], cwd=source).stdout.strip()
        dirty = bool(run(["git", "status", "--porcelain"], cwd=source).stdout.strip())
        return commit, dirty
    except (subprocess.CalledProcessError, FileNotFoundError):
        return "unknown", False


def record_tests(record: dict, t: TestRun, log_name: str) -> None:
    """A mutant's result from its test run."""
    record["tests_run"] = len(t.passed) + (t.first_failure is not None)
    record["test_seconds"] = round(record.get("test_seconds", 0.0) + t.seconds, 1)
    record["killer"], record["killer_status"] = t.first_failure, t.first_failure_status
    record["result"] = {"passed": "survived", "failed": "killed",
                        "timeout": "timeout", "error": "error"}[t.status]
    if t.status == "error":
        record["detail"] = f"ctest failed without a failing test, see {log_name}"


def run_mutant(args: argparse.Namespace, m: Mutant, build: Path, logs: Path, targets: list[str],
               programs: dict[str, Path], timeout: float, src: Path, record: dict) -> None:
    """Rebuilds and tests the tree with mutant m applied; fills in record's result."""
    # --affected-only, an RTL mutant: the tests that read the sources first, before the
    # rebuild, which a mutant they kill never needs.
    early = source_tests(programs, build) if programs and m.file.endswith(".sv") else []
    if early:
        # The build tree first follows the mutated tree: CMake reads some RTL files when it
        # configures (formal.cmake's negative tests copy them with a fault injected), and the
        # previous mutant, killed here too, may have left a configuration made from its own.
        if not configure(src, build, logs / f"{m.id}.configure.log", fatal=False):
            record["result"], record["killer"] = "killed", "cmake (configure)"
            record["killer_status"] = "configure time"
            return
        t = run_tests(args, build, logs / f"{m.id}.source.log", timeout,
                      stop_on_failure=True, only=early)
        if t.status != "passed":
            record_tests(record, t, f"{m.id}.source.log")
            return
    # Stages (--affected-only): the cheap test programs first, then everything; the tests a
    # stage's rebuild affects run before the next stage builds.
    stages = ([st for st in args.stage if set(st) <= set(targets)] if programs else []) + [targets]
    ran = set(early)
    record["build_seconds"] = 0.0
    for k, stage in enumerate(stages, 1):
        # One log a stage (a later stage's must not overwrite what an earlier one ran).
        build_log, test_log = f"{m.id}.stage{k}.build.log", f"{m.id}.stage{k}.test.log"
        before = built_programs(programs, build) if programs else {}
        ok, build_s = build_targets(args, build, stage, logs / build_log)
        record["build_seconds"] = round(record["build_seconds"] + build_s, 1)
        if not ok:
            check = compile_time_check(logs / build_log, src)
            if check:
                record["result"], record["killer"] = "killed", check
                record["killer_status"] = "compile time"
            else:
                record["result"] = "build-broken"
                record["detail"] = first_error(logs / build_log).replace(f"{src}/", "")
            return
        only = ([n for n in affected_tests(programs, before, build) if n not in ran]
                if programs else None)
        if only == []:
            continue
        t = run_tests(args, build, logs / test_log, timeout, stop_on_failure=True, only=only)
        record_tests(record, t, test_log)
        if t.status != "passed":
            return
        ran.update(only or [])
    if "result" not in record:
        record["result"] = "survived"
        record["detail"] = ("no test program was rebuilt" + (
            "; the tests that read the sources passed" if early else " and no test reads sources"))
    else:
        record["tests_run"] = len(ran)


def campaign(args: argparse.Namespace, mutants: list[Mutant], catalogue_size: int) -> int:
    source = args.source
    work = args.work_dir if args.work_dir.is_absolute() else source / args.work_dir
    src, build, logs = work / "src", work / "build", work / "logs"
    logs.mkdir(parents=True, exist_ok=True)
    if args.nice:
        os.nice(args.nice)
    os.environ.setdefault("CCACHE_DIR", str(work / "ccache"))
    # A SIGTERM unwinds like Ctrl-C, so that the mutated file is restored (--resume needs it).
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(143))
    results_file = work / "results.json"
    earlier = (json.loads(results_file.read_text())
               if args.resume and results_file.is_file() else None)
    if earlier:
        # The same campaign goes on: on its copy of the tree as it is (not synced again, so
        # that edits made since to the working tree do not mix into it), with its catalogue.
        if earlier["meta"].get("tree_key") != tree_key(src):
            sys.exit(f"mutation_test: --resume: {src} is no longer the tree of {results_file} "
                     "(run without --resume for a new campaign)")
        try:
            mutants = select(parse_catalogue(src / args.catalogue), args.only)
        except CatalogueError as e:
            sys.exit(f"mutation_test: {e}")
        print(f"resume: the campaign of {earlier['meta']['commit']} on {src}", flush=True)
    else:
        changed = sync_tree(source, src, work)
        print(f"source copy {src}: {changed} files updated", flush=True)
    problems = [p for p in (check_snippet(src, m) for m in mutants) if p]
    if problems:
        sys.exit("mutation_test: the catalogue does not apply:\n" + "\n".join(problems))
    configure(src, build, logs / "configure.log")
    targets = args.targets or hardware_targets(build)
    print(f"build {build}, targets: {' '.join(targets)}", flush=True)

    if earlier:
        meta = dict(earlier["meta"], jobs=args.jobs, build_jobs=args.build_jobs)
        wanted = {m.id for m in mutants}
        kept = [r for r in earlier["results"] if r["id"] in wanted]
    else:
        commit, dirty = git_state(source)
        meta = {"tree_key": tree_key(src), "catalogue": str(args.catalogue),
                "labels": args.labels, "exclude": args.exclude, "commit": commit, "dirty": dirty,
                "jobs": args.jobs, "build_jobs": args.build_jobs, "host": os.uname().nodename,
                "started": datetime.datetime.now(datetime.timezone.utc).strftime(
                    "%Y-%m-%d %H:%M UTC"),
                "baseline_seconds": None}
        kept = []
    timeout = args.timeout
    if earlier and meta.get("baseline_seconds") is not None:
        print(f"resume: {len(kept)} results kept; the baseline passed in that campaign",
              flush=True)
        if timeout is None:
            timeout = max(120.0, 3.0 * meta["baseline_seconds"])
    elif not args.no_baseline:
        ok, build_s = build_targets(args, build, targets, logs / "baseline.build.log")
        if not ok:
            sys.exit(f"mutation_test: the unmutated tree does not build: "
                     f"{first_error(logs / 'baseline.build.log')} (see {logs}/baseline.build.log)")
        base = run_tests(args, build, logs / "baseline.test.log", args.timeout or 7200,
                         stop_on_failure=False)
        if base.status != "passed":
            sys.exit(f"mutation_test: the unmutated tree fails its tests ({base.status}, first: "
                     f"{base.first_failure}); see {logs}/baseline.test.log")
        meta.update(baseline_build_seconds=build_s, baseline_seconds=base.seconds,
                    baseline_tests=len(base.passed))
        print(f"baseline: build {build_s:.0f} s, {len(base.passed)} tests passed in "
              f"{base.seconds:.0f} s", flush=True)
        if timeout is None:
            timeout = max(120.0, 3.0 * base.seconds)
    if timeout is None:
        timeout = 1800.0

    # --affected-only: a test whose program was not rebuilt and that reads no source file
    # cannot see the mutant (only outside tools such as Verilator and Yosys read sources).
    programs = test_programs(args, build) if args.affected_only else {}
    meta["affected_only"] = args.affected_only
    results: list[dict] = list(kept)
    done = {r["id"] for r in kept}
    for i, m in enumerate(mutants, 1):
        if m.id in done:
            continue
        path = src / m.file
        original = path.read_text(encoding="utf-8")
        if occurrences(original, m.find) != 1:
            sys.exit(f"mutation_test: {check_snippet(src, m)}")
        start = time.monotonic()
        record = {"id": m.id, "file": m.file, "what": m.what, "expected": m.expected,
                  "killer": None, "killer_status": None, "detail": ""}
        try:
            path.write_text(original.replace(m.find, m.replace, 1), encoding="utf-8")
            run_mutant(args, m, build, logs, targets, programs, timeout, src, record)
        finally:
            path.write_text(original, encoding="utf-8")
        record["seconds"] = round(time.monotonic() - start, 1)
        results.append(record)
        killer = f" by {record['killer']}" if record["killer"] else ""
        print(f"[{i}/{len(mutants)}] {m.id}: {record['result']}{killer} "
              f"({record['seconds']:.0f} s)", flush=True)
        results_file.write_text(json.dumps({"meta": meta, "results": results}, indent=1))
        if args.report:
            write_report(args.report, results, meta, catalogue_size)

    detected, relevant = kill_rate(results)
    print(f"killed {detected} of {relevant} mutants that change an output; results in "
          f"{results_file}" + (f", report {args.report}" if args.report else ""))
    return 0


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--source", type=Path, default=REPO,
                    help="the source tree (a git work tree; default: this script's repository)")
    ap.add_argument("--catalogue", type=Path, default=DEFAULT_CATALOGUE,
                    help="the mutant catalogue, relative to --source (default: %(default)s)")
    ap.add_argument("--list", action="store_true",
                    help="check that every snippet occurs exactly once in the tree and print "
                         "the catalogue; no build, exit status 1 on any problem")
    ap.add_argument("--only", nargs="+", metavar="ID",
                    help="run only these mutants (ids or shell patterns such as 'spill.*')")
    ap.add_argument("--jobs", type=int, default=2, help="ctest -j (default: %(default)s)")
    ap.add_argument("--build-jobs", type=int, default=2,
                    help="cmake --build -j (default: %(default)s)")
    ap.add_argument("--timeout", type=float,
                    help="seconds of tests per mutant before it counts as a timeout (default: "
                         "3 times the baseline's test time, at least 120)")
    ap.add_argument("--build-timeout", type=float, default=3600,
                    help="seconds of rebuild per mutant (default: %(default)s)")
    ap.add_argument("--report", type=Path, help="write the Markdown report here (e.g. "
                    "docs/mutation.md), rewritten after every mutant")
    ap.add_argument("--work-dir", type=Path, default=DEFAULT_WORK_DIR,
                    help="the source copy (src/), build directory (build/), logs and results, "
                         "relative to --source (default: %(default)s)")
    ap.add_argument("--targets", nargs="+", help="build these targets instead of every target "
                    "defined in testbench/ and any *formal* directory")
    ap.add_argument("--labels", default=DEFAULT_LABELS,
                    help="ctest -L regular expression (default: %(default)s)")
    ap.add_argument("--exclude", default=DEFAULT_EXCLUDE,
                    help="ctest -E regular expression (default: %(default)s)")
    ap.add_argument("--affected-only", action="store_true",
                    help="per mutant, run only the tests whose program was rebuilt and those "
                         "that run an outside tool (lint, synthesis, formal): the others cannot "
                         "see the mutant")
    ap.add_argument("--stage", nargs="+", action="append", metavar="TARGET",
                    help="with --affected-only: build these targets and run the tests they "
                         "affect before the next stage (repeatable; the last stage is every "
                         "target; default: " + "; ".join(" ".join(st) for st in DEFAULT_STAGES)
                         + ")")
    ap.add_argument("--resume", action="store_true",
                    help="keep the results of an earlier campaign in the work directory on the "
                         "same tree (every file but docs/ and *.md unchanged) and run only the "
                         "other mutants; the report covers both")
    ap.add_argument("--no-baseline", action="store_true",
                    help="skip building and testing the unmutated tree first")
    ap.add_argument("--nice", type=int, default=10, help="niceness of builds and tests "
                    "(default: %(default)s)")
    args = ap.parse_args()
    if args.stage is None:
        args.stage = [list(st) for st in DEFAULT_STAGES]
    args.source = args.source.resolve()
    catalogue = args.catalogue if args.catalogue.is_absolute() else args.source / args.catalogue
    try:
        mutants = parse_catalogue(catalogue)
        if args.list:
            return list_catalogue(select(mutants, args.only), args.source)
        chosen = select(mutants, args.only)
    except CatalogueError as e:
        print(f"mutation_test: {e}", file=sys.stderr)
        return 1
    if args.report and not args.report.is_absolute():
        args.report = args.source / args.report
    return campaign(args, chosen, len(mutants))


if __name__ == "__main__":
    sys.exit(main())
