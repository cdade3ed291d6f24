"""Measure how many mutated files make each reader escape with something other than InputError.

    .venv/bin/python tests/fuzz/measure_escapes.py [N per target] [target ...] [--save DIR] [--kinds K1,K2]
    .venv/bin/python tests/fuzz/measure_escapes.py --families [N per family and target] [family ...]
        [--timeout S] [--memory MIB] [--save DIR]

With ``--families`` the structure-aware families of ``families.py`` run instead, each mutant read
in a worker process (``fuzz_worker.py``) under an address-space limit (``--memory``, default
1536 MiB) and a time limit (``--timeout``, default 60 s): a mutant that passes either counts as
an escape (``MemoryError``, ``timeout``, ``killed``). One line per (family, target) with the escapes,
the largest peak resident memory of one mutant and the slowest mutant; JSON last.

Prints one line per target and, last, JSON ``{target: {"n": N, "escaped": k, "rate": k/N,
"accepted": a, "types": {...}}}`` (``accepted``: mutants read without any error).
With ``--save DIR`` every escaping mutant is written to DIR/<target>/ (the
source of the regression corpus). ``--kinds`` draws the mutations from those kinds only (one family,
e.g. ``yaml_alias``). Deterministic: mutant i of a target uses ``random.Random(i)``.
"""

from __future__ import annotations

import collections
import json
import random
import sys
import tempfile
import time
import traceback
from pathlib import Path

sys.path[:0] = [str(Path(__file__).parent), str(Path(__file__).parents[1] / "groundtruth")]

from fuzz_helpers import TARGETS, apply, make_seeds, materialize, outcome, random_mutations  # noqa: E402


def main(argv: list[str]) -> None:
    if "--families" in argv:
        argv.remove("--families")
        measure_families(argv)
        return
    save = None
    if "--save" in argv:
        i = argv.index("--save")
        save = Path(argv[i + 1])
        argv = argv[:i] + argv[i + 2 :]
    kinds = None
    if "--kinds" in argv:
        i = argv.index("--kinds")
        kinds = tuple(argv[i + 1].split(","))
        argv = argv[:i] + argv[i + 2 :]
    n = int(argv[0]) if argv else 200
    names = argv[1:] or list(TARGETS)
    out = {}
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        seeds = make_seeds(root / "seeds")
        for name in names:
            seed = seeds[name]
            data = seed.read_bytes()
            types: collections.Counter[str] = collections.Counter()
            t0 = time.perf_counter()
            accepted = 0
            for i in range(n):
                muts = random_mutations(random.Random(i), TARGETS[name].text, kinds)
                mutant = apply(data, muts)
                path = materialize(seed, mutant, root / "mutant")
                exc, read = outcome(name, path)
                accepted += read
                if exc is not None:
                    frame = traceback.extract_tb(exc.__traceback__)[-1]
                    key = f"{type(exc).__name__} at {Path(frame.filename).name}:{frame.lineno}"
                    types[key] += 1
                    if save is not None:
                        d = save / name
                        d.mkdir(parents=True, exist_ok=True)
                        (d / f"{i:05d}{seed.suffix}").write_bytes(mutant)
                        (d / f"{i:05d}.txt").write_text(f"{muts}\n{key}\n{type(exc).__name__}: {exc}"[:2000])
            k = sum(types.values())
            out[name] = {
                "n": n,
                "escaped": k,
                "rate": round(k / n, 4),
                "accepted": accepted,
                "seconds": round(time.perf_counter() - t0, 2),
                "types": dict(types.most_common()),
            }
            common = dict(types.most_common(4))
            print(f"{name:14s} {k:4d}/{n} = {100 * k / n:5.1f} %  accepted {accepted:4d}  {common}", flush=True)
    print(json.dumps(out))


class _Worker:
    """A ``fuzz_worker.py`` process under an address-space limit; restarted after a timeout or crash."""

    def __init__(self, memory_mib: int) -> None:
        import os
        import resource
        import subprocess

        limit = memory_mib * 2**20

        def limits() -> None:
            resource.setrlimit(resource.RLIMIT_AS, (limit, limit))

        env = {**os.environ, "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}
        self.proc = subprocess.Popen(
            [sys.executable, str(Path(__file__).with_name("fuzz_worker.py"))],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            text=True,
            preexec_fn=limits,
            env=env,
        )

    def ask(self, target: str, path: Path, timeout: float) -> dict | None:
        """The worker's answer, or None when it ran past ``timeout`` or died (the worker is then gone)."""
        import select

        assert self.proc.stdin is not None and self.proc.stdout is not None
        try:
            self.proc.stdin.write(json.dumps({"target": target, "path": str(path)}) + "\n")
            self.proc.stdin.flush()
        except BrokenPipeError:
            return None
        ready, _, _ = select.select([self.proc.stdout], [], [], timeout)
        line = self.proc.stdout.readline() if ready else ""
        return json.loads(line) if line else None

    def stop(self) -> None:
        self.proc.kill()
        self.proc.wait()


def measure_families(argv: list[str]) -> None:
    from families import FAMILIES, family_mutant

    opts = {"--timeout": "60", "--memory": "1536", "--save": ""}
    for flag in list(opts):
        if flag in argv:
            i = argv.index(flag)
            opts[flag] = argv[i + 1]
            argv = argv[:i] + argv[i + 2 :]
    timeout, memory = float(opts["--timeout"]), int(opts["--memory"])
    save = Path(opts["--save"]) if opts["--save"] else None
    n = int(argv[0]) if argv else 300
    names = argv[1:] or list(FAMILIES)
    out: dict[str, dict] = {}
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        seeds = make_seeds(root / "seeds")
        worker = _Worker(memory)
        for family in names:
            for target in FAMILIES[family].targets:
                seed = seeds[target]
                data = seed.read_bytes()
                types: collections.Counter[str] = collections.Counter()
                peak, slowest, t0, read_ok = 0.0, 0.0, time.perf_counter(), 0
                for i in range(n):
                    mutant = family_mutant(family, target, i, data)
                    path = materialize(seed, mutant, root / "mutant")
                    t1 = time.perf_counter()
                    ans = worker.ask(target, path, timeout)
                    took = time.perf_counter() - t1
                    if ans is None:
                        alive = worker.proc.poll() is None
                        key = "timeout" if alive else f"killed (exit {worker.proc.returncode})"
                        worker.stop()
                        worker = _Worker(memory)
                        detail = f"{key} after {took:.1f} s"
                    else:
                        key, detail = ans["escape"], ans["detail"]
                        read_ok += key is None and not ans["refused"]
                        peak = max(peak, ans["peak_mib"])
                    slowest = max(slowest, took)
                    if key is not None:
                        types[key] += 1
                        if ans is not None:  # an escape may leave the process broken (a half-imported module): start afresh
                            worker.stop()
                            worker = _Worker(memory)
                        if save is not None:
                            d = save / family / target
                            d.mkdir(parents=True, exist_ok=True)
                            (d / f"{i:05d}{seed.suffix}").write_bytes(mutant)
                            (d / f"{i:05d}.txt").write_text(f"{key}\n{detail}"[:2000])
                k = sum(types.values())
                out[f"{family}/{target}"] = {
                    "n": n,
                    "escaped": k,
                    "read": read_ok,
                    "refused": n - k - read_ok,
                    "peak_mib": peak,
                    "slowest_s": round(slowest, 2),
                    "seconds": round(time.perf_counter() - t0, 1),
                    "types": dict(types.most_common()),
                }
                print(
                    f"{family:14s} {target:14s} {k:4d}/{n} escaped ({read_ok} read, {n - k - read_ok} refused)  "
                    f"peak {peak:7.1f} MiB  slowest {slowest:5.2f} s  "
                    f"{dict(types.most_common(3))}",
                    flush=True,
                )
        worker.stop()
    print(json.dumps(out))


if __name__ == "__main__":
    main(sys.argv[1:])
