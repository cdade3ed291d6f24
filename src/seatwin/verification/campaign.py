"""``seatwin verify``: the reference agent (and its variants) over sampled encounters on the campaign engine.

One job per (family, encounter, agent): the encounter is built from its unit-cube point, sailed in the closed loop
and judged; its row (the encounter's parameters, the verdict, the run's cost) is the job's result. Jobs run on
:func:`seatwin.campaign.engine.run_jobs` (Ray, local by default; in process with ``workers=0``), cached and
resumable. The driver writes ``results.csv``, ``verify.json`` (failure rates per agent and family with Wilson 95 %
intervals, the modelled − perfect difference with its Newcombe interval, the encounters that fail only with
modelled perception, the cost), ``failure_map.png`` (nominal CPA against the target's initial relative bearing,
coloured by verdict, a panel per agent) and ``worst/`` (failed modelled runs as scenarios with the ownship's sailed
path, which ``seatwin simulate`` turns into bags).
"""

from __future__ import annotations

import json
import math
import os
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from seatwin.campaign.engine import Engine, Job, RunReport, run_jobs
from seatwin.encounters.space import EncounterSpace, latin_hypercube, random_points, space
from seatwin.verification.spec import VerifySpec, agent_name, load_verify_spec

OUTPUTS = ("results.csv", "verify.json", "failure_map.png", "worst", "jobs")


def _space(spec: VerifySpec, family: str) -> EncounterSpace:
    return space(family, run_out=spec.run_out, tcpa=spec.tcpa)


def verify_jobs(spec: VerifySpec, folder: str | os.PathLike[str] = ".") -> list[Job]:
    """Every (family, encounter, agent) job of ``spec``; a gRPC agent's command runs in ``folder`` (the spec's)."""
    jobs = []
    remote = {
        agent_name(a): None if isinstance(a, str) else {**a.model_dump(mode="json"), "cwd": str(Path(folder).resolve())}
        for a in spec.agents
    }
    for f_i, family in enumerate(spec.families):
        sp = _space(spec, family)
        draw = latin_hypercube if spec.sampler == "lhs" else random_points
        points = draw(sp.dimension, spec.encounters, spec.seed + 7919 * f_i)
        for i, u in enumerate(points):
            for agent in spec.agents:
                jobs.append(
                    Job(
                        {
                            "kind": "verify",
                            "family": family,
                            "index": i,
                            "point": [float(x) for x in u],
                            "agent": agent_name(agent),
                            **({"remote": remote[agent_name(agent)]} if remote[agent_name(agent)] else {}),
                            "seed": spec.seed + i,
                            "harbour": spec.harbour,
                            "tcpa": spec.tcpa,
                            "run_out": spec.run_out,
                            "sensors": list(spec.sensors),
                            "sensor_model": spec.sensor_model.model_dump(),
                            "safety_distance": spec.safety_distance,
                        }
                    )
                )
    return jobs


def _run(params: dict[str, Any]) -> tuple[Any, Any, Any, Any]:
    """(scenario, placement, run record, verdict) of one job's parameters; an :class:`InputError` when the encounter
    has no place on the harbour's water."""
    from seatwin.agents import make_agent
    from seatwin.encounters.build import encounter_scenario
    from seatwin.layout import harbour_map
    from seatwin.sim.settings import SimulationSettings
    from seatwin.verification.loop import run_closed_loop
    from seatwin.verification.verdict import VerdictRules, judge

    tcpa = None if params["tcpa"] is None else tuple(params["tcpa"])
    sp = space(params["family"], run_out=params["run_out"], tcpa=tcpa)
    enc = sp.encounter(params["point"])
    name = f"{params['family']}_{params['index']:04d}"
    scenario, placement = encounter_scenario(enc, name, params["harbour"], params["seed"])
    settings = SimulationSettings(seed=params["seed"], **params["sensor_model"])
    remote = params.get("remote")
    if remote is not None:
        from seatwin.api.agent_link import RemoteAgent

        assert scenario.ownship is not None
        with RemoteAgent(
            params["agent"],
            tuple(remote["sensors"]),
            address=remote["address"] or "127.0.0.1:0",
            command=remote["command"],
            timeout_s=remote["timeout_s"],
            startup_timeout_s=remote["startup_timeout_s"],
            vessel=scenario.ownship.name,
            cwd=remote["cwd"],
        ) as agent:
            rec = run_closed_loop(scenario, agent, settings)
    else:
        agent = (
            make_agent(params["agent"])
            if params["agent"] == "perfect"
            else make_agent(params["agent"], sensors=tuple(params["sensors"]))
        )
        rec = run_closed_loop(scenario, agent, settings)
    verdict = judge(rec, harbour_map(params["harbour"]), VerdictRules(safety_distance=params["safety_distance"]))
    return scenario, placement, rec, verdict


def verify_job(params: dict[str, Any], inputs: dict[str, Any]) -> dict[str, Any]:
    """One job: the encounter's parameters, the verdict's row and the run's cost; an encounter with no place on the
    harbour's water is a row with ``placed`` false and the reason (not run, not counted in the failure rates)."""
    from seatwin.encounters.geometry import target_start
    from seatwin.encounters.place import NoPlacementError

    t0, c0 = time.perf_counter(), time.process_time()
    tcpa = None if params["tcpa"] is None else tuple(params["tcpa"])
    enc = space(params["family"], run_out=params["run_out"], tcpa=tcpa).encounter(params["point"])
    head = {k: params[k] for k in ("family", "index", "agent", "seed")}
    try:
        scenario, placement, rec, verdict = _run(params)
    except NoPlacementError as exc:
        return {**head, **enc.parameters(), "placed": False, "passed": None, "reasons": exc.detail}
    starts = [target_start(enc.own_speed, t) for t in enc.targets]
    return {
        **head,
        **enc.parameters(),
        "placed": True,
        "placement_rejected": placement.rejected,
        **{f"bearing_deg_{i}": math.degrees(s.bearing) for i, s in enumerate(starts, start=1)},
        **verdict.row(),
        "nominal_cpa_1": verdict.targets[0].nominal_cpa,
        "simulated_s": float(rec.time[-1] - rec.time[0]),
        "steps": int(rec.time.size),
        "lidar_frames": rec.frames.get("lidar", 0),
        "radar_frames": rec.frames.get("radar", 0),
        "wall_s": time.perf_counter() - t0,
        "cpu_s": time.process_time() - c0,
    }


def wilson(k: int, n: int, z: float = 1.959964) -> tuple[float, float]:
    """Wilson score interval of a proportion k/n (95 % by default)."""
    if n == 0:
        return (math.nan, math.nan)
    p = k / n
    d = 1 + z * z / n
    c = (p + z * z / (2 * n)) / d
    h = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / d
    return (max(0.0, c - h), min(1.0, c + h))


def newcombe(k1: int, n1: int, k2: int, n2: int) -> tuple[float, float, float]:
    """p1 − p2 and its 95 % interval by Newcombe's hybrid score method (method 10, 1998) from Wilson intervals."""
    p1, p2 = k1 / n1, k2 / n2
    l1, u1 = wilson(k1, n1)
    l2, u2 = wilson(k2, n2)
    d = p1 - p2
    return d, d - math.sqrt((p1 - l1) ** 2 + (u2 - p2) ** 2), d + math.sqrt((u1 - p1) ** 2 + (p2 - l2) ** 2)


@dataclass
class VerifyResult:
    rows: list[dict[str, Any]]
    summary: dict[str, Any]
    report: RunReport
    out: Path


def summarise(rows: list[dict[str, Any]], agents: tuple[str, ...]) -> dict[str, Any]:
    """Failure rates per agent (and per family) with intervals, modelled − perfect, perception-only failures."""
    out: dict[str, Any] = {"agents": {}}
    for a in agents:
        mine = [r for r in rows if r["agent"] == a]
        k = sum(not r["passed"] for r in mine)
        fams = {}
        for fam in sorted({r["family"] for r in mine}):
            fr = [r for r in mine if r["family"] == fam]
            kf = sum(not r["passed"] for r in fr)
            fams[fam] = {"runs": len(fr), "failed": kf, "rate": kf / len(fr), "interval95": wilson(kf, len(fr))}
        out["agents"][a] = {
            "runs": len(mine),
            "failed": k,
            "rate": k / len(mine) if mine else math.nan,
            "interval95": wilson(k, len(mine)),
            "colreg_findings": sum(not r["colreg_ok"] for r in mine),
            "families": fams,
        }
    if "perfect" in agents:
        perfect = {(r["family"], r["index"]): r for r in rows if r["agent"] == "perfect"}
        for a in agents:
            if a == "perfect":
                continue
            mine = {(r["family"], r["index"]): r for r in rows if r["agent"] == a}
            both = sorted(set(mine) & set(perfect))
            if not both:
                continue
            k1 = sum(not mine[x]["passed"] for x in both)
            k2 = sum(not perfect[x]["passed"] for x in both)
            d, lo, hi = newcombe(k1, len(both), k2, len(both))
            out["agents"][a]["minus_perfect"] = {"difference": d, "interval95": (lo, hi), "pairs": len(both)}
            out["agents"][a]["fail_only_with_modelled_perception"] = [
                f"{f}_{i:04d}" for (f, i) in both if not mine[(f, i)]["passed"] and perfect[(f, i)]["passed"]
            ]
    return out


def placement_summary(rows: list[dict[str, Any]], harbour: str) -> dict[str, Any]:
    """How the encounters were placed: per family the jobs placed, the draws refused (a path off the water) before
    each placement, and the jobs with no place on the water in the placement's tries."""
    out: dict[str, Any] = {"harbour": harbour, "families": {}}
    for fam in sorted({r["family"] for r in rows}):
        mine = [r for r in rows if r["family"] == fam and "placed" in r]
        placed = [r for r in mine if r["placed"]]
        rejected = [int(r["placement_rejected"]) for r in placed]
        out["families"][fam] = {
            "placed": len(placed),
            "not_placed": len(mine) - len(placed),
            "rejected_draws": sum(rejected),
            "rejected_draws_mean": sum(rejected) / len(rejected) if rejected else None,
            "rejected_draws_max": max(rejected, default=None),
        }
    return out


def plot_failure_map(rows: list[dict[str, Any]], agents: tuple[str, ...], path: Path) -> Path:
    """The CPA without avoidance against the target's initial relative bearing, coloured by verdict; a panel per agent."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, len(agents), figsize=(5 * len(agents), 4.2), squeeze=False, sharey=True)
    for ax, a in zip(axes[0], agents):
        mine = [r for r in rows if r["agent"] == a]
        for ok, colour, label in ((True, "tab:green", "pass"), (False, "tab:red", "fail")):
            sel = [r for r in mine if bool(r["passed"]) == ok]
            ax.scatter(
                [r["bearing_deg_1"] for r in sel], [r["cpa_1"] for r in sel], s=14, c=colour, label=f"{label} ({len(sel)})"
            )
        colreg = [r for r in mine if r["passed"] and not r["colreg_ok"]]
        ax.scatter(
            [r["bearing_deg_1"] for r in colreg],
            [r["cpa_1"] for r in colreg],
            s=40,
            facecolors="none",
            edgecolors="tab:orange",
            label=f"COLREG finding ({len(colreg)})",
        )
        ax.set_title(f"{a}: {sum(not r['passed'] for r in mine)} of {len(mine)} fail")
        ax.set_xlabel("target's initial relative bearing [deg]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    axes[0][0].set_ylabel("CPA without avoidance, target 1 [m] (+: to starboard)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def _csv(rows: list[dict[str, Any]]) -> str:
    cols: list[str] = []
    for r in rows:
        cols += [c for c in r if c not in cols]

    def cell(v: Any) -> str:
        if v is None:
            return ""
        if isinstance(v, float):
            return repr(round(v, 6))
        text = str(v)
        return f'"{text}"' if ("," in text or '"' in text) else text

    return "\n".join([",".join(cols), *(",".join(cell(r.get(c)) for c in cols) for r in rows)]) + "\n"


def _save_worst(spec: VerifySpec, rows: list[dict[str, Any]], jobs: list[Job], out: Path) -> list[str]:
    """Re-run (deterministically) the worst failed runs of modelled perception and save them with the sailed path."""
    from dataclasses import replace

    from seatwin.scenario import Trajectory
    from seatwin.scenario.load import save_scenario

    failed = [(r, j) for r, j in zip(rows, jobs) if not r["passed"] and r["agent"] != "perfect"]
    failed.sort(key=lambda x: x[0]["min_distance"])
    names = []
    for row, job in failed[: spec.worst]:
        scenario, _, rec, _ = _run(job.params)
        own = scenario.ownship
        assert own is not None
        sailed = Trajectory(rec.time, rec.own[:, 0], rec.own[:, 1], rec.own[:, 2], source=f"{scenario.name}: sailed")
        vessels = [replace(v, trajectory=sailed) if v is own else v for v in scenario.vessels]
        name = f"{row['family']}_{row['index']:04d}_{row['agent']}"
        (out / "worst").mkdir(parents=True, exist_ok=True)
        save_scenario(
            replace(scenario, vessels=vessels, name=name, description=f"{scenario.description}; sailed by {row['agent']}"),
            out / "worst" / f"{name}.yaml",
        )
        names.append(name)
    return names


def run_verification(
    spec_path: str | os.PathLike[str],
    out: str | os.PathLike[str],
    *,
    engine: Engine = "ray",
    address: str | None = None,
    workers: int | None = None,
    progress: Callable[[int, int], None] | None = None,
    overwrite: bool = False,
) -> VerifyResult:
    """Run the verification campaign of ``spec_path`` into ``out`` (module docstring)."""
    from seatwin.campaign.folder import claim_experiment_folder
    from seatwin.outputs import write_text_atomic

    spec = load_verify_spec(spec_path)
    out = Path(out)
    claim_experiment_folder(
        out,
        "out",
        kind="verify",
        settings=spec.model_dump(mode="json"),
        files=[spec.sensor_model.radar_config],
        source=str(Path(spec_path).resolve()),
        outputs=OUTPUTS,
        overwrite=overwrite,
    )
    jobs = verify_jobs(spec, Path(spec_path).resolve().parent)
    report = run_jobs(jobs, verify_job, out, engine=engine, address=address, workers=workers, progress=progress)
    rows = []
    for job in jobs:
        rec = report.records[job.id]
        rows.append(
            rec.result
            if rec.ok
            else {**{k: job.params[k] for k in ("family", "index", "agent", "seed")}, "error": rec.error, "passed": None}
        )
    ok_rows = [r for r in rows if r.get("passed") is not None]
    summary = summarise(ok_rows, spec.agent_names)
    ran = [report.records[j.id] for j in jobs if report.records[j.id].ok and report.records[j.id].result.get("placed", True)]
    summary["placement"] = placement_summary(rows, spec.harbour)
    cost = np.array([r.result["cpu_s"] for r in ran]) if ran else np.zeros(0)
    summary["cost"] = {
        "jobs": len(jobs),
        "failed_jobs": report.n_failed,
        "cpu_s_per_run_mean": float(cost.mean()) if cost.size else None,
        "cpu_s_per_run_by_agent": {
            a: float(np.mean([r.result["cpu_s"] for r in ran if r.result["agent"] == a]))
            for a in spec.agent_names
            if any(r.result["agent"] == a for r in ran)
        },
        "simulated_s_per_run_mean": float(np.mean([r.result["simulated_s"] for r in ran])) if ran else None,
        **report.describe(),
    }
    summary["worst"] = _save_worst(spec, ok_rows, [j for j, r in zip(jobs, rows) if r.get("passed") is not None], out)
    write_text_atomic(out / "results.csv", _csv(rows))
    write_text_atomic(out / "verify.json", json.dumps(summary, indent=1, default=str) + "\n")
    if ok_rows:
        plot_failure_map(ok_rows, spec.agent_names, out / "failure_map.png")
    return VerifyResult(rows, summary, report, out)
