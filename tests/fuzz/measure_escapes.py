"""Measure how many mutated files make each reader escape with something other than InputError.

    .venv/bin/python tests/fuzz/measure_escapes.py [N per target] [target ...] [--save DIR] [--kinds K1,K2]

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


if __name__ == "__main__":
    main(sys.argv[1:])
